// Compiles: the control for the layering tests (a sim header seen from a target linking sim).
#include "vgroove/sim/groove.h"

int main() { return 0; }
