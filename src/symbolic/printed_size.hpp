#pragma once
// Length of an expression as GiNaC prints it: the measure by which `derive` chooses the shortest
// of several equivalent forms to show.

#include <ginac/ginac.h>

#include <cstddef>
#include <sstream>

namespace lagrange::symbolic {

/// Characters of GiNaC's default text form of `e`.
inline size_t printed_size(const GiNaC::ex& e) {
  std::ostringstream os;
  os << e;
  return os.str().size();
}

}  // namespace lagrange::symbolic
