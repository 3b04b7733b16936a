#pragma once
// The fixed files of every FMU's sources/ (the FMI 2.0 headers and the FMU's C), embedded at
// build time by src/io/CMakeLists.txt.

#include <vector>

namespace lagrange::fmu {

struct File {
  const char* name;  ///< file name in sources/
  const char* text;
};

/// fmi2Functions.h, fmi2FunctionTypes.h, fmi2TypesPlatform.h, LICENSE.txt (theirs), then
/// lagrange_fmu.c and the files it includes.
const std::vector<File>& files();

}  // namespace lagrange::fmu
