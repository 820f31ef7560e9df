#include "report/sample_analysis.hpp"

#include "report/number_format.hpp"

#include <algorithm>
#include <cmath>

namespace toonwater::report {

const StudySample* find(const std::vector<StudySample>& samples, const std::string& surface,
                        const std::string& sampling, const std::string& method,
                        std::size_t vertices) {
  for (const StudySample& s : samples)
    if (s.surface == surface && s.sampling == sampling && s.method == method &&
        s.vertices == vertices)
      return &s;
  return nullptr;
}

std::vector<std::size_t> resolutions(const std::vector<StudySample>& samples,
                                     const std::string& surface) {
  std::vector<std::size_t> v;
  for (const StudySample& s : samples)
    if (s.surface == surface && std::find(v.begin(), v.end(), s.vertices) == v.end())
      v.push_back(s.vertices);
  std::sort(v.begin(), v.end());
  return v;
}

double order(const StudySample& coarse, const StudySample& fine, bool mean) {
  const double e0 = mean ? coarse.rms_mean : coarse.rms_gaussian;
  const double e1 = mean ? fine.rms_mean : fine.rms_gaussian;
  return std::log(e0 / e1) / (0.5 * std::log(double(fine.vertices) / double(coarse.vertices)));
}

std::string Range::text() const { return empty() ? "n/a" : g(lo) + " to " + g(hi); }

Range error_ratio(const std::vector<StudySample>& samples, const std::string& sampling,
                  const std::string& a, const std::string& b, bool mean, std::size_t min_vertices) {
  Range r;
  for (const std::string& surface : study_surfaces)
    for (std::size_t n : resolutions(samples, surface)) {
      if (n < min_vertices) continue;
      const StudySample* x = find(samples, surface, sampling, a, n);
      const StudySample* y = find(samples, surface, sampling, b, n);
      if (x && y) r.add(mean ? x->rms_mean / y->rms_mean : x->rms_gaussian / y->rms_gaussian);
    }
  return r;
}

Range order_range(const std::vector<StudySample>& samples, const std::string& sampling,
                  const std::string& method, bool mean) {
  Range r;
  for (const std::string& surface : study_surfaces) {
    const auto n = resolutions(samples, surface);
    const StudySample* coarse = find(samples, surface, sampling, method, n.front());
    const StudySample* fine = find(samples, surface, sampling, method, n.back());
    if (coarse && fine && n.size() > 1) r.add(order(*coarse, *fine, mean));
  }
  return r;
}

std::map<std::string, int> winners(const std::vector<StudySample>& samples,
                                   const std::string& sampling) {
  std::map<std::string, int> wins;
  for (const std::string& surface : study_surfaces) {
    const std::size_t n = resolutions(samples, surface).back();
    const StudySample* best = nullptr;
    for (const Method& m : study_methods())
      if (const StudySample* s = find(samples, surface, sampling, m.name, n))
        if (!best || s->rms_mean + s->rms_gaussian < best->rms_mean + best->rms_gaussian) best = s;
    if (best) ++wins[best->method];
  }
  return wins;
}

}  // namespace toonwater::report
