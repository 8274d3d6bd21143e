// What the grader can observe of a student's NewtonsApple.cpp: its simulation of a scene, its model, and its answer
// to the trade question, measured.
#include "apple/grading/observations.h"
#include "simlab/probe/probe.h"

SIMLAB_PROBE(appleObservations) {
    simlab::probe::addLab<apple::Sample, apple::Scene, apple::Model>();
    simlab::probe::addTrade<apple::Sample, apple::Scene, apple::Model>(apple::cheapestSettings, apple::readState);
}
