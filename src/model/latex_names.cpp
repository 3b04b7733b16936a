#include "model/latex_names.hpp"

#include <cctype>
#include <set>

namespace lagrange::model {

namespace {

bool is_greek(const std::string& s) {
  static const std::set<std::string> greek = {
      "alpha",   "beta",   "gamma", "delta",   "epsilon", "zeta",  "eta",   "theta",  "iota",
      "kappa",   "lambda", "mu",    "nu",      "xi",      "pi",    "rho",   "sigma",  "tau",
      "upsilon", "phi",    "chi",   "psi",     "omega",   "Gamma", "Delta", "Theta",  "Lambda",
      "Xi",      "Pi",     "Sigma", "Upsilon", "Phi",     "Psi",   "Omega", "varphi", "vartheta"};
  return greek.count(s) != 0;
}

/// One word as LaTeX: Greek letters get a backslash, single letters stay, longer words are upright.
std::string word(const std::string& w) {
  if (is_greek(w)) return "\\" + w;
  if (w.size() <= 1) return w;
  bool digits = true;
  for (char c : w) digits = digits && std::isdigit(static_cast<unsigned char>(c));
  if (digits) return w;
  std::string escaped;
  for (char c : w) escaped += c == '_' ? std::string("\\_") : std::string(1, c);
  return "\\mathrm{" + escaped + "}";
}

}  // namespace

std::string latex_name(const std::string& name, const std::string& accent) {
  std::string base = name, sub;
  size_t us = name.find('_');
  // An element's dotted name (drum.reeled_out) is one word: its underscore is no subscript.
  const size_t dot = name.find('.');
  if (dot != std::string::npos && dot < us) {
    const std::string out = word(name);
    return accent.empty() ? out : accent + "{" + out + "}";
  }
  if (us != std::string::npos && us > 0) {
    base = name.substr(0, us);
    sub = name.substr(us + 1);
  } else {
    size_t end = name.size();
    while (end > 1 && std::isdigit(static_cast<unsigned char>(name[end - 1]))) --end;
    base = name.substr(0, end);
    sub = name.substr(end);
  }
  std::string out = word(base);
  if (!accent.empty()) out = accent + "{" + out + "}";
  if (!sub.empty()) out += "_{" + word(sub) + "}";
  return out;
}

}  // namespace lagrange::model
