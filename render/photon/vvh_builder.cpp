// The voxel-volume-heuristic photon map builder (Fabianowski & Dingliana 2009, section 5.1,
// eq. 14, after [WGS04]; count-threshold termination of section 5.3). Owns the top-down split
// search, the depth bound and the flattening into photon_map.h's node layout; see vvh_builder.h
// for the layout, the node numbering and the flat-box padding.
//
// Method: the hits are sorted once per axis by AABB centroid (key lo + hi, ties by input index).
// Each of the three sorted copies carries the boxes, so every sweep reads memory sequentially.
// At a node holding positions [b, e) of all three copies (the same set of hits, each copy in its
// own axis order), the 3 (N - 1) plane positions are scored with a suffix sweep (V_R N_R per
// split) and a prefix sweep (V_L N_L + V_R N_R). The winning axis' copy is already split at the
// chosen position; the other two are partitioned stably with a per-hit flag, so they stay sorted
// and the children again hold [b, b + k) and [b + k, e) of all three copies. O(N) per level.
#include "render/photon/vvh_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pm {
namespace {

constexpr uint32_t kLeafBit = 0x80000000u;  // PM_PHOTON_MAP_LEAF

struct Item {
  float lo[3];
  float hi[3];
  uint32_t id;
  float key;  // lo + hi on this copy's axis (2 x centroid); non-finite sorts last
};

struct Box {
  float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                 std::numeric_limits<float>::infinity()};
  float hi[3] = {-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                 -std::numeric_limits<float>::infinity()};

  void grow(const float* l, const float* h)
  {
    for (int a = 0; a < 3; ++a) {
      lo[a] = l[a] < lo[a] ? l[a] : lo[a];
      hi[a] = h[a] > hi[a] ? h[a] : hi[a];
    }
  }
};

// Eq. 14's V with every extent padded by `pad` (see kVvhFlatEpsilon).
double padded_volume(const float* lo, const float* hi, double pad)
{
  double v = 1.0;
  for (int a = 0; a < 3; ++a) v *= (double)hi[a] - (double)lo[a] + pad;
  return v;
}

float as_float(uint32_t u) { return PM_UINT_AS_FLOAT(u); }

struct Builder {
  uint32_t threshold = 1;
  std::vector<Item> items[3];
  std::vector<Item> tmp;
  std::vector<uint8_t> goes_left;   // by input index
  std::vector<double> right_cost;   // by split offset k: V_R * N_R of [b + k, e)
  VvhPhotonMap* out = nullptr;

  void write_slot(uint32_t node, int side, const Box& box, uint32_t ref, uint32_t count)
  {
    std::vector<float4>& nodes = out->nodes;
    nodes[4 * node + 2 * side] = PM_MAKE_FLOAT4(box.lo[0], box.lo[1], box.lo[2], as_float(ref));
    nodes[4 * node + 2 * side + 1] = PM_MAKE_FLOAT4(box.hi[0], box.hi[1], box.hi[2], as_float(count));
  }

  // Inner node `node` at `level` (root = 1) over positions [b, e), e - b >= 2.
  void build(uint32_t node, uint32_t b, uint32_t e, int level)
  {
    out->depth = std::max(out->depth, level);
    const uint32_t c = e - b;
    // Depth bound: an inner child at level + 1 holding c' hits can always be finished by median
    // splits within ceil(log2 c') further levels, so require c' <= 2^(kVvhMaxDepth - level).
    // The median split satisfies this whenever this node did (the root: n < 2^31 <= 2^59).
    const int spare = kVvhMaxDepth - level;
    const uint64_t cap = spare >= 40 ? ~uint64_t{0} : (uint64_t{1} << std::max(spare, 0));
    auto allowed = [&](uint32_t count) { return count <= threshold || count <= cap; };
    // Flat-box pad relative to this node's box (the choice is scale invariant; 0 if all hits
    // coincide, when every split costs the same and the balance tie-break decides).
    Box node_box;
    for (uint32_t j = b; j < e; ++j) node_box.grow(items[0][j].lo, items[0][j].hi);
    double extent = 0.0;
    for (int a = 0; a < 3; ++a) extent = std::max(extent, (double)node_box.hi[a] - (double)node_box.lo[a]);
    const double pad = std::isfinite(extent) ? kVvhFlatEpsilon * extent : 0.0;

    int best_axis = -1;
    uint32_t best_k = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    uint32_t best_imbalance = 0;
    for (int a = 0; a < 3; ++a) {
      const Item* it = items[a].data();
      Box right;
      for (uint32_t j = e - 1; j > b; --j) {  // right = [j, e), k = j - b
        right.grow(it[j].lo, it[j].hi);
        right_cost[j - b] = padded_volume(right.lo, right.hi, pad) * (double)(e - j);
      }
      Box left;
      for (uint32_t j = b; j + 1 < e; ++j) {  // left = [b, j], k = j - b + 1
        left.grow(it[j].lo, it[j].hi);
        const uint32_t k = j - b + 1;
        if (!allowed(k) || !allowed(c - k)) continue;
        const double cost = padded_volume(left.lo, left.hi, pad) * (double)k + right_cost[k];
        const uint32_t imbalance = k > c - k ? k - (c - k) : (c - k) - k;
        // Costs within a relative 1e-9 are ties (rounding makes equal costs differ in the last
        // bits); ties go to the more balanced split.
        const bool lower = cost < best_cost - 1e-9 * best_cost;
        const bool tie = !lower && cost <= best_cost + 1e-9 * best_cost;
        if ((best_axis < 0 && !std::isnan(cost)) || lower || (tie && imbalance < best_imbalance)) {
          best_axis = a;
          best_k = k;
          best_cost = cost;
          best_imbalance = imbalance;
        }
      }
    }
    if (best_axis < 0) {  // only NaN costs (non-finite input): median on x
      best_axis = 0;
      best_k = c / 2;
    }
    const uint32_t k = best_k;

    // Partition the other two copies stably; boxes of both children from the winning copy.
    Box left_box, right_box;
    for (uint32_t j = b; j < e; ++j) {
      const Item& item = items[best_axis][j];
      const bool l = j < b + k;
      goes_left[item.id] = l ? 1 : 0;
      (l ? left_box : right_box).grow(item.lo, item.hi);
    }
    for (int a = 0; a < 3; ++a) {
      if (a == best_axis) continue;
      Item* it = items[a].data();
      uint32_t l = b, r = 0;
      for (uint32_t j = b; j < e; ++j) {
        if (goes_left[it[j].id]) it[l++] = it[j];
        else tmp[r++] = it[j];
      }
      std::copy(tmp.begin(), tmp.begin() + r, it + l);
    }

    // Children: leaves at <= T, otherwise inner nodes numbered like a Karras tree's.
    const uint32_t left_count = k, right_count = c - k;
    const bool left_leaf = left_count <= threshold, right_leaf = right_count <= threshold;
    const uint32_t left_ref = left_leaf ? (b | kLeafBit) : b + k - 1;
    const uint32_t right_ref = right_leaf ? ((b + k) | kLeafBit) : b + k;
    write_slot(node, 0, left_box, left_ref, left_count);
    write_slot(node, 1, right_box, right_ref, right_count);
    out->leaves += (left_leaf ? 1 : 0) + (right_leaf ? 1 : 0);
    if (!left_leaf) build(left_ref, b, b + k, level + 1);
    if (!right_leaf) build(right_ref, b + k, e, level + 1);
  }
};

}  // namespace

VvhPhotonMap build_vvh_photon_map(const std::vector<float4>& lo, const std::vector<float4>& hi,
                                  uint32_t leaf_threshold)
{
  if (lo.size() != hi.size()) throw std::invalid_argument("build_vvh_photon_map: lo and hi differ in size");
  if (lo.size() >= (size_t{1} << 31)) throw std::invalid_argument("build_vvh_photon_map: more than 2^31 - 1 hits");
  const uint32_t n = (uint32_t)lo.size();
  VvhPhotonMap map;
  map.order.resize(n);
  for (uint32_t i = 0; i < n; ++i) map.order[i] = i;
  if (n < 2) {
    map.leaves = n;
    return map;
  }

  Builder builder;
  builder.out = &map;
  builder.threshold = std::max<uint32_t>(leaf_threshold, 1u);
  for (int a = 0; a < 3; ++a) {
    std::vector<Item>& v = builder.items[a];
    v.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      Item& it = v[i];
      const float l[3] = {lo[i].x, lo[i].y, lo[i].z}, h[3] = {hi[i].x, hi[i].y, hi[i].z};
      for (int d = 0; d < 3; ++d) {
        it.lo[d] = l[d];
        it.hi[d] = h[d];
      }
      it.id = i;
      const float key = l[a] + h[a];
      it.key = std::isnan(key) ? std::numeric_limits<float>::infinity() : key;
    }
    std::sort(v.begin(), v.end(),
              [](const Item& p, const Item& q) { return p.key < q.key || (p.key == q.key && p.id < q.id); });
  }
  builder.tmp.resize(n);
  builder.goes_left.assign(n, 0);
  builder.right_cost.assign(n, 0.0);

  // Unused node numbers (inside leaves) get empty boxes, which contain no point.
  Box empty;
  const float4 empty_lo = PM_MAKE_FLOAT4(empty.lo[0], empty.lo[1], empty.lo[2], as_float(0));
  const float4 empty_hi = PM_MAKE_FLOAT4(empty.hi[0], empty.hi[1], empty.hi[2], as_float(0));
  map.nodes.resize(4 * size_t(n - 1));
  for (size_t p = 0; p < n - 1; ++p)
    for (int s = 0; s < 2; ++s) {
      map.nodes[4 * p + 2 * s] = empty_lo;
      map.nodes[4 * p + 2 * s + 1] = empty_hi;
    }

  builder.build(0, 0, n, 1);
  for (uint32_t i = 0; i < n; ++i) map.order[i] = builder.items[0][i].id;
  return map;
}

double photon_map_expected_cost(const std::vector<float4>& nodes, size_t n, double flat_pad)
{
  if (n < 2 || nodes.size() < 4) return 0.0;
  double cost = 0.0;
  std::vector<uint32_t> stack{0u};
  size_t visited = 0;
  const size_t node_count = nodes.size() / 4;
  while (!stack.empty()) {
    const uint32_t p = stack.back();
    stack.pop_back();
    if (p >= node_count || ++visited > node_count)
      throw std::invalid_argument("photon_map_expected_cost: malformed tree");
    for (int s = 0; s < 2; ++s) {
      const float4 l = nodes[4 * p + 2 * s], h = nodes[4 * p + 2 * s + 1];
      const float lo[3] = {l.x, l.y, l.z}, hi[3] = {h.x, h.y, h.z};
      const uint32_t ref = PM_AS_UINT(l.w), count = PM_AS_UINT(h.w);
      cost += padded_volume(lo, hi, flat_pad) * (double)count;
      if (!(ref & kLeafBit)) stack.push_back(ref);
    }
  }
  return cost;
}

}  // namespace pm
