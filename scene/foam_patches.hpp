// Foam as a cartoon draws it: flat patches on the water where foam particles gather, following
// the water as they do.
//
// Each foam particle spreads foam over a ball of radius R, `reach` pixels at its distance from
// the camera, with the density of a metaball, (1 − r²/R²)² at distance r; foam shows on the
// water's surface wherever the particles' densities add up to `density` (Blinn 1982; POV-Ray's
// `blob`, whose components are exactly these). So a patch is where particles crowd, as many
// within a reach on screen whatever the simulation's resolution; a lone particle, or a sparse
// spread, paints nothing; a patch's edge is a smooth curve that moves as its particles move, and
// it grows and shrinks as they come and go instead of popping. The water's own surface is
// painted (POV-Ray's `object` pattern), so a patch lies on the surface by construction.
//
// Simulators keep foam a little under the surface (Mantaflow: about a cell), where a ball of a
// few pixels would barely reach it; so each particle is moved onto the tangent plane of the
// nearest water vertex, along its normal, when it lies within kFoamSearch reaches of that
// plane; a particle farther from the water is no foam on it. Give the water as analysed, not
// simplified: its vertices lie about an edge apart everywhere.
//
// Particles are summed into cells half a reach wide (at the median particle's distance), each a
// component at the particles' mean position that keeps their amount of foam (∝ S·R³) and their
// spread (the kernel's mean squared reach is R²/3, so R² grows by three times the particles'
// mean squared distance from their mean): the field differs from the particles' own by a few
// per cent, and a frame holds at most kMaxFoamComponents (the cells grow until it does).
// Particles whose ball cannot reach the image are left out.
#pragma once

#include "analyzer/mesh.hpp"
#include "scene/scene_mesh.hpp"
#include "scene/screen_projection.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace toonwater {

// A component of the foam's field: `strength` particles at `centre`, reaching `radius`.
struct FoamComponent {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
  double strength = 0.0;
};

struct FoamOptions {
  double reach_pixels = 6.0;
  double density = 6.0;  // the field's value at a patch's edge, in particles
};

// The most components a frame's foam is written with.
inline constexpr std::size_t kMaxFoamComponents = 4000;

// How far from the water's surface, in reaches, a foam particle still counts as its foam.
inline constexpr double kFoamSearch = 2.0;

// The components of a frame's foam on `water` (POV-Ray's frame); none when no particle reaches
// the image.
std::vector<FoamComponent> foam_components(std::span<const Vec3> foam, const SceneMesh& water,
                                           const ScreenProjection& screen,
                                           const FoamOptions& options);

// The foam field at p: what POV-Ray's blob sums.
double foam_field(std::span<const FoamComponent> components, const Vec3& p);

}  // namespace toonwater
