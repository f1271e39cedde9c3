#pragma once
// Presenting evaluation results: one JSON object (machine-readable, the keys
// of issue #3) or a table for a person.
#include <iosfwd>

#include "edgevio/eval/metrics.h"

namespace edgevio::eval {

void writeJson(std::ostream& out, const EvalResult& r);
void writeTable(std::ostream& out, const EvalResult& r);

}  // namespace edgevio::eval
