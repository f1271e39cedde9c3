#include <ostream>

#include "edgevio/cli/commands.h"

namespace edgevio::cli {
int eval(const EvalArgs&, std::ostream&, std::ostream& err) { return notImplemented("eval", "issue 3", err); }
}  // namespace edgevio::cli
