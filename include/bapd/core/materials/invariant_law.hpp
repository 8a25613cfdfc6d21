#pragma once
// What the header of a law of invariants (law.hpp) needs: the law interface, the
// formulations that make it a model (Compressible3D, PlaneStrain: hyperelastic.hpp;
// PlaneStress: plane_stress.hpp) and what its options and checks are written with.
#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include "bapd/core/materials/hyperelastic.hpp"
#include "bapd/core/materials/law.hpp"
#include "bapd/core/materials/plane_stress.hpp"
