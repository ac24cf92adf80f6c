// Builds the scene BVH (stage S0): binned SAH over triangle centroids, top-down and depth-first,
// with a median-split fallback and a depth guard; then flattens it into the float4 layout
// documented in scene_bvh.h.
#include "render/scene_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "render/errors.h"

namespace pm {
namespace {

constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;
// Below this many triangles a node is always a leaf; SAH is not worth evaluating.
constexpr int kMinLeafSize = 4;
// Relative box padding: 2^-20 is about 8 ulps of the padded coordinate.
constexpr float kPadRelative = 1.0f / (1 << 20);
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Aabb {
  float lo[3] = {kInf, kInf, kInf};
  float hi[3] = {-kInf, -kInf, -kInf};

  void grow(const float p[3]) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  void grow(const Aabb& b) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], b.lo[a]);
      hi[a] = std::max(hi[a], b.hi[a]);
    }
  }
  bool empty() const { return !(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2]); }
  // Half the surface area: SAH only ever uses ratios, so the factor 2 is irrelevant.
  float half_area() const {
    if (empty()) return 0.0f;
    float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return dx * dy + dy * dz + dz * dx;
  }
};

// One child as its parent stores it.
struct ChildRef {
  Aabb box;
  int32_t index = -1;  // leaf: first leaf-order triangle; inner: node index; -1: empty
  int32_t count = 0;   // leaf triangle count, 0 for inner and empty children
};

struct Bin {
  Aabb box;
  int count = 0;
};

// Inner levels that repeated median splits need to bring n triangles down to leaves of at
// most kSceneBvhMaxLeafSize: 0 for a leaf, 1 + levels(ceil(n/2)) otherwise.
int median_levels_needed(size_t n) {
  int levels = 0;
  while (n > static_cast<size_t>(kSceneBvhMaxLeafSize)) {
    n = (n + 1) / 2;
    ++levels;
  }
  return levels;
}

class Builder {
 public:
  Builder(const Scene& scene, const SceneBvhOptions& options, SceneBvh& out)
      : scene_(scene), out_(out) {
    bin_count_ = std::clamp(options.bin_count, 2, 256);
    const size_t n = scene.triangle_count();
    // The root (level 1) with n triangles needs median_levels_needed(n) inner levels at least.
    max_depth_ = std::max({options.max_depth, median_levels_needed(n), 1});
    bins_.resize(3 * static_cast<size_t>(bin_count_));
    tri_box_.resize(n);
    centroid_.resize(n);
    order_.resize(n);
    Aabb scene_box;
    for (size_t t = 0; t < n; ++t) {
      for (int v = 0; v < 3; ++v) {
        const Float3& p = scene.positions[scene.indices[3 * t + v]];
        const float xyz[3] = {p.x, p.y, p.z};
        tri_box_[t].grow(xyz);
      }
      for (int a = 0; a < 3; ++a)
        centroid_[t].c[a] = 0.5f * (tri_box_[t].lo[a] + tri_box_[t].hi[a]);
      scene_box.grow(tri_box_[t]);
      order_[t] = static_cast<uint32_t>(t);
    }
    float extent = 0.0f;
    if (!scene_box.empty())
      for (int a = 0; a < 3; ++a) extent = std::max(extent, scene_box.hi[a] - scene_box.lo[a]);
    pad_absolute_ = std::isfinite(extent) ? kPadRelative * extent : 0.0f;
  }

  void build() {
    const size_t n = order_.size();
    out_.nodes.reserve(4 * std::max<size_t>(1, n / 2));
    ChildRef root = build_range(0, n, 1);
    if (root.count > 0 || root.index < 0) {
      // One leaf's worth of triangles (or none): a root with the leaf left and nothing right.
      allocate_node();
      write_node(0, root, ChildRef{});
      out_.depth = 1;
    }
    // The flattened tree always has a root node, so a leaf root still pays one traversal.
    const float root_area = root.box.half_area();
    if (root.count > 0) area_weighted_cost_ += kTraversalCost * root_area;
    out_.sah_cost = root_area > 0.0f ? static_cast<float>(area_weighted_cost_ / root_area) : 0.0f;
    write_triangles();
  }

 private:
  struct Centroid {
    float c[3];
  };

  // Builds the subtree over order_[begin, end) whose top sits at inner level `depth` and returns
  // it as its parent will store it.
  ChildRef build_range(size_t begin, size_t end, int depth) {
    ChildRef ref;
    const size_t n = end - begin;
    if (n == 0) return ref;
    Aabb box, centroid_box;
    for (size_t i = begin; i < end; ++i) {
      box.grow(tri_box_[order_[i]]);
      centroid_box.grow(centroid_[order_[i]].c);
    }
    ref.box = box;
    const float leaf_cost = kIntersectionCost * static_cast<float>(n) * box.half_area();

    // Leaves are forced below kMinLeafSize and at the depth limit (where the guard below
    // guarantees n <= kSceneBvhMaxLeafSize).
    if (n <= static_cast<size_t>(kMinLeafSize) || depth > max_depth_) return make_leaf(ref, begin, n);

    size_t mid = begin;
    bool split_found = false;
    Split split = find_sah_split(begin, end, centroid_box);
    if (split.axis >= 0) {
      const float split_cost = kTraversalCost * box.half_area() + split.cost;
      if (n <= static_cast<size_t>(kSceneBvhMaxLeafSize) && leaf_cost <= split_cost)
        return make_leaf(ref, begin, n);
      // Depth guard: take the SAH split only if both sides can still reach leaves by median
      // splits within the limit; otherwise the median split below always can.
      const bool within_depth = depth + median_levels_needed(split.left_count) <= max_depth_ &&
                                depth + median_levels_needed(n - split.left_count) <= max_depth_;
      if (within_depth) {
        mid = partition_at(begin, end, split, centroid_box);
        // Partitioning re-bins exactly as find_sah_split did, so the sizes match; checking
        // anyway keeps the depth guarantee independent of that.
        split_found = mid - begin == split.left_count && mid > begin && mid < end;
      }
    } else if (n <= static_cast<size_t>(kSceneBvhMaxLeafSize)) {
      // No usable SAH split (coincident centroids, or areas overflowing float): a small node
      // stays a leaf, a large one falls through to the median split.
      return make_leaf(ref, begin, n);
    }
    if (!split_found) mid = median_split(begin, end, centroid_box);

    const int32_t node = allocate_node();
    out_.depth = std::max(out_.depth, depth);
    area_weighted_cost_ += kTraversalCost * box.half_area();
    ChildRef left = build_range(begin, mid, depth + 1);
    ChildRef right = build_range(mid, end, depth + 1);
    write_node(node, left, right);
    ref.index = node;
    ref.count = 0;
    return ref;
  }

  struct Split {
    int axis = -1;
    int last_left_bin = -1;  // bins [0, last_left_bin] go left
    size_t left_count = 0;
    float cost = kInf;  // intersection part of the SAH, in area-weighted units
  };

  // Bin scale per axis over the centroid bounds, or 0 where the axis cannot be binned.
  float bin_scale(const Aabb& centroid_box, int axis) const {
    const float extent = centroid_box.hi[axis] - centroid_box.lo[axis];
    if (!(extent > 0.0f)) return 0.0f;
    const float scale = static_cast<float>(bin_count_) / extent;
    return std::isfinite(scale) ? scale : 0.0f;  // a denormal extent overflows the scale
  }

  int bin_of(uint32_t tri, int axis, float lo, float scale) const {
    // fmaxf/fminf drop NaN, so a non-finite centroid lands in bin 0 instead of undefined casts.
    const float v = (centroid_[tri].c[axis] - lo) * scale;
    return static_cast<int>(std::fminf(std::fmaxf(v, 0.0f), static_cast<float>(bin_count_ - 1)));
  }

  Split find_sah_split(size_t begin, size_t end, const Aabb& centroid_box) {
    Split best;
    float scale[3];
    for (int a = 0; a < 3; ++a) scale[a] = bin_scale(centroid_box, a);
    if (scale[0] == 0.0f && scale[1] == 0.0f && scale[2] == 0.0f) return best;
    Bin* bins[3] = {&bins_[0], &bins_[bin_count_], &bins_[2 * bin_count_]};
    std::fill(bins_.begin(), bins_.end(), Bin{});

    for (size_t i = begin; i < end; ++i) {
      const uint32_t tri = order_[i];
      for (int a = 0; a < 3; ++a) {
        if (scale[a] == 0.0f) continue;
        Bin& bin = bins[a][bin_of(tri, a, centroid_box.lo[a], scale[a])];
        bin.box.grow(tri_box_[tri]);
        ++bin.count;
      }
    }
    float right_area[256];
    int right_count[256];
    for (int a = 0; a < 3; ++a) {
      if (scale[a] == 0.0f) continue;
      // Sweep from the right: right_*[b] describes bins [b, bin_count).
      Aabb acc;
      int count = 0;
      for (int b = bin_count_ - 1; b > 0; --b) {
        acc.grow(bins[a][b].box);
        count += bins[a][b].count;
        right_area[b] = acc.half_area();
        right_count[b] = count;
      }
      acc = Aabb();
      count = 0;
      for (int b = 0; b < bin_count_ - 1; ++b) {
        acc.grow(bins[a][b].box);
        count += bins[a][b].count;
        if (count == 0 || right_count[b + 1] == 0) continue;  // both sides must be non-empty
        const float cost = kIntersectionCost * (acc.half_area() * static_cast<float>(count) +
                                                right_area[b + 1] * static_cast<float>(right_count[b + 1]));
        if (cost < best.cost) {
          best.cost = cost;
          best.axis = a;
          best.last_left_bin = b;
          best.left_count = static_cast<size_t>(count);
        }
      }
    }
    return best;
  }

  size_t partition_at(size_t begin, size_t end, const Split& split, const Aabb& centroid_box) {
    const int axis = split.axis;
    const float lo = centroid_box.lo[axis];
    const float scale = bin_scale(centroid_box, axis);
    auto first_right = std::partition(order_.begin() + begin, order_.begin() + end, [&](uint32_t tri) {
      return bin_of(tri, axis, lo, scale) <= split.last_left_bin;
    });
    return static_cast<size_t>(first_right - order_.begin());
  }

  // Splits at the middle index along the widest centroid axis; works for coincident centroids
  // too (nth_element still yields two halves), which is what bounds the depth.
  size_t median_split(size_t begin, size_t end, const Aabb& centroid_box) {
    int axis = 0;
    float widest = -1.0f;
    for (int a = 0; a < 3; ++a) {
      const float extent = centroid_box.hi[a] - centroid_box.lo[a];
      if (extent > widest) {
        widest = extent;
        axis = a;
      }
    }
    const size_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](uint32_t a, uint32_t b) { return centroid_[a].c[axis] < centroid_[b].c[axis]; });
    return mid;
  }

  ChildRef make_leaf(ChildRef ref, size_t begin, size_t n) {
    ref.index = static_cast<int32_t>(begin);
    ref.count = static_cast<int32_t>(n);
    ++out_.leaf_count;
    area_weighted_cost_ += kIntersectionCost * static_cast<float>(n) * ref.box.half_area();
    return ref;
  }

  int32_t allocate_node() {
    const size_t index = out_.nodes.size() / 4;
    out_.nodes.resize(out_.nodes.size() + 4);
    return static_cast<int32_t>(index);
  }

  // Padded bounds as stored for the device; empty boxes stay inverted (+INF, -INF).
  void padded(const Aabb& box, float lo[3], float hi[3]) const {
    for (int a = 0; a < 3; ++a) {
      if (box.empty()) {
        lo[a] = kInf;
        hi[a] = -kInf;
        continue;
      }
      lo[a] = box.lo[a] - (kPadRelative * std::fabs(box.lo[a]) + pad_absolute_);
      hi[a] = box.hi[a] + (kPadRelative * std::fabs(box.hi[a]) + pad_absolute_);
    }
  }

  void write_node(int32_t node, const ChildRef& left, const ChildRef& right) {
    float llo[3], lhi[3], rlo[3], rhi[3];
    padded(left.box, llo, lhi);
    padded(right.box, rlo, rhi);
    float4* n = &out_.nodes[4 * static_cast<size_t>(node)];
    n[0] = float4{llo[0], lhi[0], llo[1], lhi[1]};
    n[1] = float4{rlo[0], rhi[0], rlo[1], rhi[1]};
    n[2] = float4{llo[2], lhi[2], rlo[2], rhi[2]};
    n[3] = float4{PM_AS_FLOAT(left.index), PM_AS_FLOAT(right.index), PM_AS_FLOAT(left.count),
                  PM_AS_FLOAT(right.count)};
  }

  void write_triangles() {
    const size_t n = order_.size();
    out_.original_index = order_;
    out_.triangles.resize(3 * n);
    for (size_t i = 0; i < n; ++i) {
      const uint32_t tri = order_[i];
      const Float3& v0 = scene_.positions[scene_.indices[3 * tri + 0]];
      const Float3& v1 = scene_.positions[scene_.indices[3 * tri + 1]];
      const Float3& v2 = scene_.positions[scene_.indices[3 * tri + 2]];
      // Masked materials flag their triangles, so traversal tests the mask on those alone.
      uint32_t material = scene_.triangle_material[tri];
      if (material < scene_.materials.size() && scene_.materials[material].alpha_mask) material |= PM_TRIANGLE_MASKED;
      out_.triangles[3 * i + 0] = float4{v0.x, v0.y, v0.z, PM_UINT_AS_FLOAT(material)};
      out_.triangles[3 * i + 1] = float4{v1.x, v1.y, v1.z, PM_AS_FLOAT(tri)};
      const uint32_t object = scene_object_of(scene_, tri);
      out_.triangles[3 * i + 2] = float4{v2.x, v2.y, v2.z, PM_AS_FLOAT(object)};
    }
  }

  const Scene& scene_;
  SceneBvh& out_;
  int bin_count_ = 32;
  int max_depth_ = kSceneBvhMaxDepth;
  float pad_absolute_ = 0.0f;
  double area_weighted_cost_ = 0.0;  // sum of unnormalized SAH terms; double: 100k+ terms
  std::vector<Bin> bins_;  // scratch for find_sah_split: bin_count_ bins per axis
  std::vector<Aabb> tri_box_;
  std::vector<Centroid> centroid_;
  std::vector<uint32_t> order_;  // triangle indices; ends up in leaf order
};

void validate(const Scene& scene) {
  if (scene.indices.size() % 3 != 0)
    throw InputError("scene '" + scene.name + "': index count " + std::to_string(scene.indices.size()) +
                     " is not a multiple of 3");
  const size_t n = scene.triangle_count();
  if (n > static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    throw InputError("scene '" + scene.name + "': too many triangles for 32-bit BVH indices");
  if (scene.triangle_material.size() != n)
    throw InputError("scene '" + scene.name + "': " + std::to_string(scene.triangle_material.size()) +
                     " triangle materials for " + std::to_string(n) + " triangles");
  for (uint32_t material : scene.triangle_material)
    if (material > PM_TRIANGLE_MATERIAL_BITS)
      throw InputError("scene '" + scene.name + "': material index " + std::to_string(material) +
                       " is above the triangle records' limit " + std::to_string(PM_TRIANGLE_MATERIAL_BITS));
  if (scene.triangle_object.size() > n)
    throw InputError("scene '" + scene.name + "': " + std::to_string(scene.triangle_object.size()) +
                     " triangle objects for " + std::to_string(n) + " triangles");
  for (size_t i = 0; i < scene.indices.size(); ++i)
    if (scene.indices[i] >= scene.positions.size())
      throw InputError("scene '" + scene.name + "': vertex index " + std::to_string(scene.indices[i]) +
                       " out of range (" + std::to_string(scene.positions.size()) + " vertices)");
}

}  // namespace

SceneBvh build_scene_bvh(const Scene& scene) { return build_scene_bvh(scene, SceneBvhOptions{}); }

SceneBvh build_scene_bvh(const Scene& scene, const SceneBvhOptions& options) {
  validate(scene);
  SceneBvh bvh;
  Builder builder(scene, options, bvh);
  builder.build();
  return bvh;
}

}  // namespace pm
