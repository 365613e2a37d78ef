// A surface that has passed check_surface (surface.h): every face indexes inside V, and every
// coordinate is finite. Only the check makes one, so a stage that takes a CheckedSurface knows its
// input is sound and does not check it again: the public entry points (slim_supports,
// analyse_overhang, voxel_domain, embed_surface, tetgen_domain, optimize_orientation) check once,
// the stages behind them take this type.
//
//   const CheckedSurface checked(surface);   // throws std::invalid_argument, as check_surface
//   checked.get().V, checked.get().F
//
// It is a view: it borrows the surface, which must outlive it. Whoever moves the surface's
// vertices afterwards (the optimizer writes its iterates into a surface it owns) must keep them
// finite; the faces must not change.
#pragma once

#include "core/geometry/surface.h"

namespace slim {

class CheckedSurface {
 public:
  explicit CheckedSurface(const Surface& s) : s_(&s) { check_surface(s); }
  const Surface& get() const { return *s_; }

  // A view of a surface derived from this one without a second check: the same number of
  // vertices at finite positions (a copy, or the optimizer's iterates), and the same faces or the
  // same faces with their corners reordered (turned over). The caller vouches for it.
  CheckedSurface derived(const Surface& s) const { return CheckedSurface(&s); }

 private:
  explicit CheckedSurface(const Surface* s) : s_(s) {}
  const Surface* s_;
};

}  // namespace slim
