// Median edge length from a deterministic sample of edges; stated in edge_length.hpp.
#include "analyzer/edge_length.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace toonwater {

EdgeSample::EdgeSample(std::size_t face_count, std::size_t max_samples)
    : face_count_(face_count),
      stride_(std::max<std::size_t>(1, 3 * face_count / std::max<std::size_t>(1, max_samples))) {}

double median_length(std::vector<double>& squared_lengths) {
  if (squared_lengths.empty()) return 0.0;
  // The square root of the middle square, as Eigen's norm() takes it.
  const auto middle =
      squared_lengths.begin() + static_cast<std::ptrdiff_t>(squared_lengths.size() / 2);
  std::nth_element(squared_lengths.begin(), middle, squared_lengths.end());
  return std::sqrt(*middle);
}

double median_edge_length(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                          std::size_t max_samples) {
  const EdgeSample sample(triangles.size(), max_samples);
  // The sampled edges' lengths chunk by chunk (each a cache miss or two), then joined in order.
  const std::size_t workers = chunk_count(sample.count(), 4096);
  std::vector<std::vector<double>> chunk_lengths(workers);
  parallel_chunks(sample.count(), workers,
                  [&](std::size_t chunk, std::size_t begin, std::size_t end) {
                    // Filled in a local and moved once: the chunks' vectors share a cache line,
                    // which every push_back would otherwise write.
                    std::vector<double> lengths;
                    lengths.reserve(end - begin);
                    for (std::size_t i = begin; i < end; ++i) {
                      const double squared_length =
                          EdgeSample::squared_length(positions, triangles, i * sample.stride());
                      if (EdgeSample::counts(squared_length)) lengths.push_back(squared_length);
                    }
                    chunk_lengths[chunk] = std::move(lengths);
                  });
  std::vector<double> lengths = std::move(chunk_lengths[0]);
  for (std::size_t w = 1; w < workers; ++w)
    lengths.insert(lengths.end(), chunk_lengths[w].begin(), chunk_lengths[w].end());
  return median_length(lengths);
}

}  // namespace toonwater
