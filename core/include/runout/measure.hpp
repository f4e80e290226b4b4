// Measurements of SPEC §6 (thesis chapter 4), computed from the disc state. Pure functions of
// the state: no caches, no side effects.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "runout/neighbor_list.hpp"
#include "runout/particles.hpp"
#include "runout/walls.hpp"

namespace runout {

// Which species plays "small" and "large": the smallest and largest nominal diameters present.
struct SpeciesRoles {
  int small = 0;
  int large = 0;
};

Eigen::Vector2d centre_of_mass(const Particles& p);                     // eq. 4.1
double translational_energy(const Particles& p);                        // eq. 4.5
double rotational_energy(const Particles& p);
double potential_energy(const Particles& p, double gravity);            // above y = 0

// Translational kinetic energy of the discs that touch at least one other disc (the mass; a
// lone disc rolling away on the floor is not part of it) — or of all discs when fewer than half
// touch another (a single disc, a spray).
double mass_kinetic_energy(const Particles& p, const PairContacts& pairs);

// Height of a point above the bed: distance to the nearest bed segment (incline or floor).
double height_above_bed(const std::vector<Segment>& segments, const Eigen::Vector2d& point);

// Mean centre height above the bed of the small and of the large discs (§4.2.2).
struct SegregationHeights {
  double small = 0, large = 0;
};
SegregationHeights mean_heights(const Particles& p, const std::vector<Segment>& segments,
                                SpeciesRoles roles);

// Mean centre height above the bed per species (NaN for a species with no disc): segregation
// class by class in a polydisperse pile.
std::vector<double> mean_heights_by_species(const Particles& p, const std::vector<Segment>& segments,
                                            int species_count);

// Mean omega sqrt(d/g) of the small discs touching the bed (large ones when there are no small
// ones); clockwise (forward rolling down-slope) is negative (§4.2.3). NaN if none touch.
double basal_spin(const Particles& p, const std::vector<Segment>& segments, SpeciesRoles roles,
                  double unit_time);

// The body of a deposit along x: bins of width `bin`; a bin counts if its disc area is at least
// `min_fill` of the fullest bin's (0: any disc); the body is the run of counting bins around the
// fullest one, bridging at most `max_gap` bins that do not count. Returns {x_start, x_end}.
std::pair<double, double> deposit_extent(const Particles& p, double bin, double min_fill, int max_gap);

// The deposit's basal layer (§4.2.1, eqs. 4.6–4.9): the lowest large disc per bin of width D
// along x gives a lower contour (its bottom edge); small discs whose centre lies below the
// contour form the layer. With more than two species, "small" is the smallest class present
// and every larger disc draws the contour. H_layer = pi sum r^2 / (L C) over windows L = L1, 3/4, 1/2, 1/4 L1
// centred on the deposit centroid; L1 is the unbroken stretch of D-wide bins holding at least a
// tenth of the fullest bin's disc area (the scattered ends left out).
struct BasalLayer {
  std::vector<char> member;             // per disc: 1 if in the basal layer
  double deposit_start = 0, deposit_end = 0;  // L1's ends (x)
  std::array<double, 4> thickness{};    // H_layer for L1, 3/4, 1/2, 1/4 L1 (m)
  double mean_thickness = 0;            // mean of the four
  double spread = 0;                    // half of max - min of the four
};
BasalLayer basal_layer(const Particles& p, const std::vector<Segment>& segments,
                       SpeciesRoles roles, double large_diameter, double packing);

// Geologists' H/L: from the top of the mass at release (highest disc edge) to the farthest disc
// edge at rest (SPEC §6).
struct FrontReach {
  double top_x = 0, top_y = 0;  // highest point of the initial mass
};
FrontReach highest_point(const Particles& p);
double farthest_edge_x(const Particles& p);

}  // namespace runout
