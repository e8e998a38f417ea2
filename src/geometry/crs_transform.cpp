// PROJ adapter: every PROJ status is turned into a ProjectionError here, at the seam.
#include "relief/geometry/crs_transform.h"

#include <proj.h>

#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

#include "relief/core/errors.h"

namespace relief {
namespace {

struct ContextDeleter {
  void operator()(PJ_CONTEXT* c) const { proj_context_destroy(c); }
};
struct PjDeleter {
  void operator()(PJ* p) const { proj_destroy(p); }
};
struct ListDeleter {
  void operator()(PJ_OBJ_LIST* l) const { proj_list_destroy(l); }
};
struct FactoryDeleter {
  void operator()(PJ_OPERATION_FACTORY_CONTEXT* f) const { proj_operation_factory_context_destroy(f); }
};
using ContextPtr = std::unique_ptr<PJ_CONTEXT, ContextDeleter>;
using PjPtr = std::unique_ptr<PJ, PjDeleter>;

std::string last_error(PJ_CONTEXT* ctx) {
  const int err = proj_context_errno(ctx);
  const char* text = err ? proj_context_errno_string(ctx, err) : nullptr;
  return text ? text : "unknown PROJ error";
}

ContextPtr make_context() {
  ContextPtr ctx(proj_context_create());
  if (!ctx) throw ProjectionError("cannot create a PROJ context");
  proj_log_level(ctx.get(), PJ_LOG_NONE);
  return ctx;
}

PjPtr make_crs(PJ_CONTEXT* ctx, std::string_view definition) {
  // A bare PROJ string ("+proj=tmerc ...", as in OpenDRIVE geoReference) names a CRS here.
  std::string text(definition);
  if (text.rfind("+proj=", 0) == 0 && text.find("+type=crs") == std::string::npos) text += " +type=crs";
  PjPtr crs(proj_create(ctx, text.c_str()));
  if (!crs) {
    throw ProjectionError("unknown coordinate reference system '" + std::string(definition) +
                          "': " + last_error(ctx));
  }
  return crs;
}

}  // namespace

struct CrsTransform::Impl {
  ContextPtr ctx;
  PjPtr op;  // normalised for visualisation: x = lon/easting, y = lat/northing
  std::string name;
  std::optional<double> accuracy;
  bool better_missing = false;
  std::string missing_grids;
  // A PROJ context and its operations serve one thread at a time; the pipeline samples the DEM
  // from a stage running beside another.
  mutable std::mutex mutex;
};

CrsTransform::CrsTransform(std::string_view from, std::string_view to, std::optional<LonLatBox> area)
    : impl_(std::make_unique<Impl>()) {
  impl_->ctx = make_context();
  PJ_CONTEXT* ctx = impl_->ctx.get();
  const PjPtr src = make_crs(ctx, from);
  const PjPtr dst = make_crs(ctx, to);

  // List every candidate operation, including those whose grids are absent, most relevant first.
  std::unique_ptr<PJ_OPERATION_FACTORY_CONTEXT, FactoryDeleter> factory(
      proj_create_operation_factory_context(ctx, nullptr));
  proj_operation_factory_context_set_spatial_criterion(ctx, factory.get(),
                                                       PROJ_SPATIAL_CRITERION_PARTIAL_INTERSECTION);
  proj_operation_factory_context_set_grid_availability_use(ctx, factory.get(),
                                                           PROJ_GRID_AVAILABILITY_IGNORED);
  if (area) {
    proj_operation_factory_context_set_area_of_interest(ctx, factory.get(), area->min_lon, area->min_lat,
                                                        area->max_lon, area->max_lat);
  }
  std::unique_ptr<PJ_OBJ_LIST, ListDeleter> ops(
      proj_create_operations(ctx, src.get(), dst.get(), factory.get()));
  const int count = ops ? proj_list_get_count(ops.get()) : 0;

  PjPtr chosen;
  double best_missing_accuracy = std::numeric_limits<double>::infinity();
  std::string best_missing_grids;
  for (int i = 0; i < count; ++i) {
    PjPtr candidate(proj_list_get(ctx, ops.get(), i));
    if (!candidate) continue;
    if (proj_coordoperation_is_instantiable(ctx, candidate.get())) {
      if (!chosen) chosen = std::move(candidate);
      continue;
    }
    const double acc = proj_coordoperation_get_accuracy(ctx, candidate.get());
    if (acc >= 0.0 && acc < best_missing_accuracy) {
      best_missing_accuracy = acc;
      best_missing_grids.clear();
      const int grids = proj_coordoperation_get_grid_used_count(ctx, candidate.get());
      for (int g = 0; g < grids; ++g) {
        const char* short_name = nullptr;
        int available = 0;
        proj_coordoperation_get_grid_used(ctx, candidate.get(), g, &short_name, nullptr, nullptr, nullptr,
                                          nullptr, nullptr, &available);
        if (short_name && !available) {
          if (!best_missing_grids.empty()) best_missing_grids += ", ";
          best_missing_grids += short_name;
        }
      }
    }
  }
  if (!chosen) {
    // Fall back to PROJ's own choice (e.g. a ballpark transformation).
    chosen.reset(proj_create_crs_to_crs_from_pj(ctx, src.get(), dst.get(), nullptr, nullptr));
    if (!chosen) {
      throw ProjectionError("no transformation from '" + std::string(from) + "' to '" + std::string(to) +
                            "': " + last_error(ctx));
    }
  }
  impl_->name = proj_get_name(chosen.get()) ? proj_get_name(chosen.get()) : "";
  const double acc = proj_coordoperation_get_accuracy(ctx, chosen.get());
  if (acc >= 0.0) {
    impl_->accuracy = acc;
  } else if (proj_get_type(chosen.get()) == PJ_TYPE_CONVERSION) {
    impl_->accuracy = 0.0;  // a map projection on one datum is exact
  }
  if (!best_missing_grids.empty() && (!impl_->accuracy || best_missing_accuracy < *impl_->accuracy)) {
    impl_->better_missing = true;
    impl_->missing_grids = best_missing_grids;
  }
  impl_->op.reset(proj_normalize_for_visualization(ctx, chosen.get()));
  if (!impl_->op) {
    throw ProjectionError("cannot normalise the transformation from '" + std::string(from) + "' to '" +
                          std::string(to) + "': " + last_error(ctx));
  }
}

CrsTransform::~CrsTransform() = default;
CrsTransform::CrsTransform(CrsTransform&&) noexcept = default;
CrsTransform& CrsTransform::operator=(CrsTransform&&) noexcept = default;

namespace {

// One point through `op` in `direction`; throws with the operation's name on failure.
Vec2 transform_point(PJ* op, PJ_DIRECTION direction, const Vec2& p, const std::string& name) {
  proj_errno_reset(op);
  const PJ_COORD r = proj_trans(op, direction, proj_coord(p.x(), p.y(), 0.0, 0.0));
  if (proj_errno(op) != 0 || !std::isfinite(r.xy.x) || r.xy.x == HUGE_VAL) {
    throw ProjectionError("cannot transform point (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) +
                          ")" + (direction == PJ_INV ? " back" : "") + " with '" + name + "'");
  }
  return {r.xy.x, r.xy.y};
}

}  // namespace

Vec2 CrsTransform::apply(const Vec2& p) const {
  const std::lock_guard lock(impl_->mutex);
  return transform_point(impl_->op.get(), PJ_FWD, p, impl_->name);
}

Vec2 CrsTransform::apply_inverse(const Vec2& p) const {
  const std::lock_guard lock(impl_->mutex);
  return transform_point(impl_->op.get(), PJ_INV, p, impl_->name);
}

void CrsTransform::apply(std::span<Vec2> points) const {
  if (points.empty()) return;
  const std::lock_guard lock(impl_->mutex);
  double* x = points.data()->data();
  double* y = x + 1;
  proj_trans_generic(impl_->op.get(), PJ_FWD, x, sizeof(Vec2), points.size(), y, sizeof(Vec2), points.size(),
                     nullptr, 0, 0, nullptr, 0, 0);
  for (auto& p : points) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || p.x() == HUGE_VAL) {
      p = Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
    }
  }
}

Aabb2 CrsTransform::transform_bounds(const Aabb2& box) const {
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
  const std::lock_guard lock(impl_->mutex);
  if (!proj_trans_bounds(impl_->ctx.get(), impl_->op.get(), PJ_FWD, box.min.x(), box.min.y(), box.max.x(),
                         box.max.y(), &xmin, &ymin, &xmax, &ymax, 21)) {
    throw ProjectionError("cannot transform a bounding box with '" + impl_->name +
                          "': " + last_error(impl_->ctx.get()));
  }
  Aabb2 out;
  out.extend(Vec2(xmin, ymin));
  out.extend(Vec2(xmax, ymax));
  return out;
}

const std::string& CrsTransform::operation_name() const {
  return impl_->name;
}
std::optional<double> CrsTransform::accuracy_m() const {
  return impl_->accuracy;
}
bool CrsTransform::better_operation_missing_grid() const {
  return impl_->better_missing;
}
const std::string& CrsTransform::missing_grids() const {
  return impl_->missing_grids;
}

std::string crs_identifier(std::string_view crs) {
  const ContextPtr ctx = make_context();
  const PjPtr obj = make_crs(ctx.get(), crs);
  const char* auth = proj_get_id_auth_name(obj.get(), 0);
  const char* code = proj_get_id_code(obj.get(), 0);
  if (auth && code) return std::string(auth) + ":" + code;
  const char* name = proj_get_name(obj.get());
  return name ? name : std::string(crs);
}

std::string crs_proj_string(std::string_view crs) {
  const ContextPtr ctx = make_context();
  const PjPtr obj = make_crs(ctx.get(), crs);
  const char* text = proj_as_proj_string(ctx.get(), obj.get(), PJ_PROJ_5, nullptr);
  if (!text) throw ProjectionError("'" + std::string(crs) + "' has no PROJ string form");
  std::string out = text;
  const auto type = out.find(" +type=crs");
  if (type != std::string::npos) out.erase(type);
  return out;
}

}  // namespace relief
