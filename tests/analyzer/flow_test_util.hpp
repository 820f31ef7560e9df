// The flow stage on a test mesh, z up: its curvature and its flow regions.
#pragma once

#include "analyzer/flow_regions.hpp"
#include "tests/analyzer/curvature_test_util.hpp"

namespace toonwater::test {

struct Flow {
  Curvature curvature;
  FlowRegions regions;
};

inline Flow flow_of(const TriangleMesh& mesh, FlowOptions options = {}) {
  options.up = Axis::z;
  Flow f{curvature_of(mesh), {}};
  f.regions = find_flow_regions(f.curvature.mesh, f.curvature.topology, f.curvature.field, options);
  return f;
}

}  // namespace toonwater::test
