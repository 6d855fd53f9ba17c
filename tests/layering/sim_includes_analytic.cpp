// Must NOT compile: a target that links vgroove::sim (and not vgroove::analytic) includes an
// analytic header. The ctest `layering_sim_cannot_see_analytic` builds this and expects failure.
#include "vgroove/analytic/ndf.h"

int main() { return static_cast<int>(vgroove::analytic::D_ggx(0.0, 0.5)); }
