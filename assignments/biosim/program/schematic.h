// The schematic of a project's model, drawn from the model itself: the multibody tree (Ground, each body with
// its mass and inertia, each joint with its type, axis and degrees of freedom) as a Graphviz graph, and a picture
// of the model at t = 0. The lab program writes both into the project folder (--schematic); the grader puts them
// in the student's feedback.
#pragma once

#include <string>
#include <vector>

#include "Simbody.h"

namespace biosim {

struct Model;

/// One body of the tree, with the joint (mobilizer) that connects it to its parent.
struct SchematicBody {
    std::string name;        ///< the name in Model::bodies ("A"), or "body 3" for a body not named there
    int index = 0;           ///< mobilized body index (Ground is 0, never listed)
    int parent = 0;          ///< the parent's index (0: Ground)
    double mass = 0;         ///< kg
    SimTK::Vec3 com;         ///< m, the mass center from the body's origin, in the body's frame
    SimTK::Vec3 moments;     ///< kg m^2, central inertia Ixx, Iyy, Izz in the body's frame
    SimTK::Vec3 products;    ///< kg m^2, central products Ixy, Ixz, Iyz
    std::string joint;       ///< the mobilizer's kind: "Pin", "Slider", "Ball", "Free", ... ("Custom" if unknown)
    int dof = 0;             ///< its mobilities
    std::vector<SimTK::Vec3> axes;  ///< unit axes of its motion, in Ground at t = 0 (Pin: the rotation axis)
    SimTK::Vec3 jointLocation;      ///< m, the joint (the inboard frame's origin) in Ground at t = 0
    SimTK::Vec3 origin;             ///< m, the body's origin in Ground at t = 0
    SimTK::Vec3 massCenter;         ///< m, the body's mass center in Ground at t = 0
    /// m, in Ground at t = 0: the ends of the rods and lines the body is drawn with (a DecorativeCylinder's end
    /// centres, a DecorativeLine's points), so that a rod is drawn to its end and not only to its mass center
    std::vector<SimTK::Vec3> ends;
};

struct Schematic {
    std::string title;                  ///< the declaration's title
    std::vector<SchematicBody> bodies;  ///< in index order
    int degreesOfFreedom = 0;           ///< mobilities less independent constraints
    int constraints = 0;                ///< constraint equations
};

/// Read the schematic from a built model whose state `state` is at t = 0 (realized to Position or beyond is not
/// required: this realizes it).
Schematic schematicOf(const Model& model, const SimTK::State& state, const std::string& title);

/// The tree as a Graphviz graph (the DOT language): a node per body (name, mass, central inertia) and Ground, an
/// edge per joint (type, axis, degrees of freedom). Every name is quoted and escaped.
std::string treeDot(const Schematic& schematic);

/// The model at t = 0 as an SVG picture: two orthographic views (from +z: x right, y up; from +x: z left,
/// y up), each joint a ring, each mass center a disk sized by its mass, a line from each joint to its body's mass
/// center and on to the joints it carries; names beside them; a scale bar. Every text is escaped for XML.
std::string pictureSvg(const Schematic& schematic);

/// `dot` rendered as SVG by Graphviz's `dot -Tsvg`. Throws std::runtime_error, in one line, if Graphviz is not
/// installed or fails.
std::string renderSvg(const std::string& dot);

}  // namespace biosim
