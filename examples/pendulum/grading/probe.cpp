// What the grader can observe of a student's Pendulum.cpp: its simulation of a scene, and its model.
#include "pendulum/grading/observations.h"
#include "simlab/probe/probe.h"

SIMLAB_PROBE(pendulumObservations) { simlab::probe::addLab<pendulum::Sample, pendulum::Scene, pendulum::Model>(); }
