#pragma once
// The report's front-end (web/: three.js, uPlot, KaTeX and web/src), built by esbuild and
// embedded into the binary at build time (cmake/embed_report.cmake), so that writing a report
// needs no node at run time.

#include <string_view>

namespace lagrange::io {

std::string_view report_script();
std::string_view report_style();

}  // namespace lagrange::io
