#pragma once
// Command-line flags that name one of a choice table's values (common/options.h).
#include <cstddef>
#include <string>

#include "edgevio/common/error.h"
#include "edgevio/common/options.h"

namespace edgevio::cli {

/// Sets *out to the value `name` names; InputError "FLAG: 'name' is not one of a | b" otherwise.
template <class E, std::size_t N>
void parseFlagChoice(const char* flag, const std::string& name, const options::Choice<E> (&choices)[N], E* out) {
  if (!options::parseChoice(choices, name, out))
    throw InputError(std::string(flag) + ": '" + name + "' is not one of " + options::choiceList(choices));
}

}  // namespace edgevio::cli
