// What the grader can observe of a student's MyLab.cpp: its simulation of a scene, and its model.
//
// CHANGE: nothing, unless your lab asks a trade question too (see the apple lab's probe).
#include "mylab/grading/observations.h"
#include "simlab/probe/probe.h"

SIMLAB_PROBE(mylabObservations) { simlab::probe::addLab<mylab::Sample, mylab::Scene, mylab::Model>(); }
