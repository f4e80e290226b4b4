// Polydisperse piles (the thesis's future work, SPEC §7): a continuous size distribution by
// area — uniform (equal area in equal steps of d) or lognormal (ln d normal by area) between
// two bounds — is split into classes equal in ln d. Each class is a species: its own contact
// stiffness (designed at its nominal diameter), time step and measurements, as for the
// thesis's two species. Pure functions.
#pragma once

#include <vector>

#include "runout/scene.hpp"

namespace runout {

// The classes of one distribution: `family` carries the distribution, its bounds, its area
// share and its name; the classes are named NAME_1 (smallest) .. NAME_N, or NAME if N = 1.
std::vector<SpeciesDef> split_into_classes(const SpeciesDef& family, int classes);

// E[1/d^2] over the species' area distribution: count = area * 4/pi * E[1/d^2]. For the
// thesis's spread it is 1/nominal^2 (the count of SPEC eq. 3.1).
double mean_inverse_square_diameter(const SpeciesDef& species);

// The smallest diameter the time step must resolve: a class's lower bound; for the thesis's
// spread the nominal one (its ±10 % lies within the step's margin, SPEC §3).
double smallest_diameter(const SpeciesDef& species);

// `count` diameters of a class, the quantiles (k + 1/2)/count of its number distribution (the
// area distribution divided by d^2), smallest first: the drawn sizes follow the distribution
// exactly, whatever the seed.
std::vector<double> class_diameters(const SpeciesDef& species, int count);

}  // namespace runout
