#pragma once
// The list of grip regions (the registry: region_registry.hpp says what a region type
// is and how to add one). Included by scene_loading.hpp, whose LoadSet::Region it makes.
//
// X(id, alias, type): LoadSet::Region::<id>, its -load_NAME_region word (the id) and
// a second word (nullptr: none), made by <type>_region. The order is LoadSet::Region's.
#define BAPD_REGISTERED_REGIONS(X) \
  X(top, "y+", edge)               \
  X(bottom, "y-", edge)            \
  X(left, "x-", edge)              \
  X(right, "x+", edge)             \
  X(box, nullptr, box)             \
  X(polygon, nullptr, polygon)     \
  X(curve, nullptr, curve)         \
  X(group, nullptr, group)         \
  X(block, nullptr, block)         \
  X(front, "z+", edge)             \
  X(back, "z-", edge)
