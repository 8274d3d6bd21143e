// What the grader can observe of a student's NewtonsApple.cpp: its simulation of a scene, and its model.
#include "apple/observations.h"
#include "simlab/probe.h"

SIMLAB_PROBE(appleObservations) { simlab::probe::addLab<apple::Sample, apple::Scene, apple::Model>(); }
