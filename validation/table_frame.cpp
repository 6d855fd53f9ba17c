#include "vgroove/validation/table_frame.h"

#include "vgroove/support/format.h"
#include "vgroove/support/printable.h"
#include "vgroove/validation/report.h"

namespace vgroove::validation {

void print_table_title(std::ostream& os, std::string_view name, std::string_view kind, const std::string& detail,
                       int threads) {
  os << support::printable(name) << " (" << support::printable(kind) << "): ";
  if (!detail.empty()) os << detail << ", ";
  os << support::format("vgroove %s (git %s), %d threads\n", version_string(), git_revision(), threads);
}

void print_table_close(std::ostream& os, std::size_t passed, std::size_t total, double wall_s, std::string_view what) {
  os << support::format("  %zu/%zu ", passed, total) << what << support::format("; wall %.2f s\n", wall_s);
}

}  // namespace vgroove::validation
