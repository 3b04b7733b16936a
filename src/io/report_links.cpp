// Rigid links of the report's scene, found from the motion itself: whatever keeps two points at
// a constant distance (a rod, a body, a distance constraint) is drawn as a link between them, so
// elements need not say how they look.

#include <algorithm>
#include <cmath>
#include <set>

#include "io/report_scene.hpp"

namespace lagrange::io {

namespace {

using Frames = std::vector<std::vector<std::array<double, 3>>>;

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace

std::vector<size_t> sample_rows(size_t rows, size_t keep) {
  std::vector<size_t> out;
  if (rows == 0) return out;
  keep = std::max<size_t>(std::min(keep, rows), rows > 1 ? 2 : 1);
  for (size_t i = 0; i < keep; ++i)
    out.push_back(keep == 1 ? 0 : (i * (rows - 1) + (keep - 1) / 2) / (keep - 1));
  out.back() = rows - 1;
  return out;
}

double round_decimals(double x, int decimals) {
  if (!std::isfinite(x)) return x;
  decimals = std::clamp(decimals, -290, 290);
  const double scale = std::pow(10.0, std::abs(decimals));
  return decimals >= 0 ? std::round(x * scale) / scale : std::round(x / scale) * scale;
}

std::vector<std::pair<size_t, size_t>> rigid_links(
    const Frames& pos, double extent, const std::vector<std::pair<size_t, size_t>>& exclude,
    size_t max_links) {
  if (pos.empty()) return {};
  const size_t n = pos[0].size();
  const double still = 1e-6 * extent;
  std::vector<bool> moving(n, false);
  for (size_t i = 0; i < n; ++i)
    for (const auto& frame : pos)
      if (distance(frame[i], pos[0][i]) > still) {
        moving[i] = true;
        break;
      }
  const std::set<std::pair<size_t, size_t>> skip(exclude.begin(), exclude.end());
  struct Link {
    double length;
    size_t a, b;
  };
  std::vector<Link> links;
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n; ++b) {
      if (!moving[a] && !moving[b]) continue;
      if (skip.count({a, b}) || skip.count({b, a})) continue;
      const double d0 = distance(pos[0][a], pos[0][b]);
      if (d0 < 1e-3 * extent) continue;
      bool constant = true;
      for (const auto& frame : pos)
        if (std::abs(distance(frame[a], frame[b]) - d0) > 1e-6 * std::max(d0, extent)) {
          constant = false;
          break;
        }
      if (constant) links.push_back({d0, a, b});
    }
  std::sort(links.begin(), links.end(),
            [](const Link& x, const Link& y) { return x.length < y.length; });
  // A link through a third linked point in line with it (a straight rod with a point halfway)
  // is already drawn by its two halves.
  std::set<std::pair<size_t, size_t>> linked;
  for (const Link& l : links) linked.insert({l.a, l.b});
  auto has = [&](size_t a, size_t b) { return linked.count({std::min(a, b), std::max(a, b)}) > 0; };
  std::vector<std::pair<size_t, size_t>> out;
  for (const Link& l : links) {
    bool through = false;
    for (size_t k = 0; k < n && !through; ++k)
      through = k != l.a && k != l.b && has(l.a, k) && has(k, l.b) &&
                distance(pos[0][l.a], pos[0][k]) + distance(pos[0][k], pos[0][l.b]) <=
                    l.length * (1 + 1e-6);
    if (!through) out.emplace_back(l.a, l.b);
    if (out.size() >= max_links) break;
  }
  return out;
}

}  // namespace lagrange::io
