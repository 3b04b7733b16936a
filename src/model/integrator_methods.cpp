// The integrator names a model file and the command line accept (include/lagrange/integrator.hpp);
// kept in the model library so that the reader can check `simulate: {integrator: …}` itself.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "lagrange/integrator.hpp"

namespace lagrange {

const std::vector<std::string>& integrator_methods() {
  static const std::vector<std::string> names{"dop853",
                                              "arkode",
                                              "arkode:heun-euler",
                                              "arkode:bogacki-shampine",
                                              "arkode:zonneveld",
                                              "arkode:sayfy-aburub",
                                              "arkode:cash-karp",
                                              "arkode:fehlberg",
                                              "arkode:dormand-prince",
                                              "arkode:verner65",
                                              "arkode:fehlberg78",
                                              "arkode:verner87",
                                              "cvode",
                                              "cvode:jacobian",
                                              "auto",
                                              "rk4",
                                              "midpoint",
                                              "ida",
                                              "ida:jacobian"};
  return names;
}

std::string integrator_method_list() {
  return fmt::format("{}", fmt::join(integrator_methods(), ", "));
}

}  // namespace lagrange
