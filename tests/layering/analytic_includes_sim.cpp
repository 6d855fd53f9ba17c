// Must NOT compile: a target that links vgroove::analytic (and not vgroove::sim) includes a sim
// header. The ctest `layering_analytic_cannot_see_sim` builds this and expects failure.
#include "vgroove/sim/groove.h"

int main() { return 0; }
