#include "sim/tracer.h"

namespace vgroove::sim {

const char* termination_name(Termination t) {
  switch (t) {
    case Termination::escaped: return "escaped";
    case Termination::blocked: return "blocked";
    case Termination::vertex_hit: return "vertex_hit";
    case Termination::bounce_limit: return "bounce_limit";
  }
  return "?";
}

}  // namespace vgroove::sim
