// The examples' scenes, simulated frame by frame (Y up, water at rest at y = 0):
//   wake        a sphere crossing open water faster than its waves: a bow wave and a V wake
//   drop        a sphere dropped into a pool, sending out concentric ripples
//   reflection  two balls hovering over rippling water, for concrete and abstract reflection
//   refraction  a fish-shaped body of water with bones inside (water_figure.hpp)
// Output names: water_NNNN.obj per frame (N from 1, four digits), moving objects as
// NAME_NNNN.obj per frame, static objects as NAME.obj.
#pragma once

#include "analyzer/mesh.hpp"

#include <functional>
#include <string>
#include <vector>

namespace toonwater::sim {

struct SimulationRequest {
  std::string scenario;
  int frames = 24;
  int resolution = 0;  // grid cells along the longer side (refraction: segments); 0: default
};

// Receives each output mesh with its file name; frame meshes arrive in frame order.
using MeshSink = std::function<void(const std::string& file_name, const TriangleMesh& mesh)>;
using SimulationProgress = std::function<void(int frames_done, int frames)>;

const std::vector<std::string>& scenario_names();
int default_resolution(const std::string& scenario);

// Throws std::invalid_argument for an unknown scenario, frames < 1 or a resolution outside
// [8, 2048].
void simulate(const SimulationRequest& request, const MeshSink& sink,
              const SimulationProgress& progress);

std::string frame_file_name(const std::string& stem, int frame);

}  // namespace toonwater::sim
