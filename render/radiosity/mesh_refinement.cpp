// Mesh refinement by conforming edge-midpoint splitting, with the refinement tree that locates
// points of the original triangles in the refined ones (mesh_refinement.h).
#include "render/radiosity/mesh_refinement.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

#include "render/errors.h"

namespace pm {

namespace {

// Rounds of splitting; every round shortens the longest edge by a factor of at least 0.87 (a
// half edge, a midline, a median of a triangle whose other edges are short, or the shorter
// diagonal of a quad), so this is far beyond any real max_edge.
constexpr int kMaxRounds = PM_RADIOSITY_MAX_TREE_DEPTH - 1;

struct Node {
  float uv[3][2];
  uint32_t v[3];
  uint32_t source;
  uint32_t first_child = 0, child_count = 0;
};

double distance(const Float3& a, const Float3& b) {
  const double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double triangle_area(const Float3& a, const Float3& b, const Float3& c) {
  const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  const double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

uint64_t edge_key(uint32_t a, uint32_t b) { return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a; }

struct PositionKey {
  uint32_t bits[3];
  bool operator==(const PositionKey& o) const { return std::memcmp(bits, o.bits, sizeof(bits)) == 0; }
};
struct PositionHash {
  size_t operator()(const PositionKey& k) const {
    return (size_t(k.bits[0]) * 73856093u) ^ (size_t(k.bits[1]) * 19349663u) ^ (size_t(k.bits[2]) * 83492791u);
  }
};

class Refiner {
 public:
  Refiner(const Scene& scene, double max_edge, RefinedMesh& out) : scene_(scene), max_edge_(max_edge), out_(out) {}

  void run() {
    weld();
    const size_t t_count = scene_.triangle_count();
    nodes_.resize(t_count);
    std::vector<uint32_t> active(t_count);
    for (size_t t = 0; t < t_count; ++t) {
      Node& n = nodes_[t];
      const float uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
      std::memcpy(n.uv, uv, sizeof(uv));
      for (int k = 0; k < 3; ++k) n.v[k] = welded_[scene_.indices[3 * t + k]];
      n.source = uint32_t(t);
      active[t] = uint32_t(t);
    }
    leaves_ = t_count;
    for (int round = 0; !active.empty(); ++round) {
      mark_long_edges(active);
      if (midpoints_.empty()) break;
      if (round >= kMaxRounds)
        throw SettingError("max-edge", "refinement did not converge in " + std::to_string(kMaxRounds) + " rounds");
      std::vector<uint32_t> next;
      for (uint32_t node : active) split(node, next);
      out_.depth = round + 1;
      active.swap(next);
    }
    write();
  }

 private:
  void weld() {
    std::unordered_map<PositionKey, uint32_t, PositionHash> seen;
    welded_.resize(scene_.positions.size());
    for (size_t i = 0; i < scene_.positions.size(); ++i) {
      const Float3& p = scene_.positions[i];
      PositionKey key;
      std::memcpy(&key.bits[0], &p.x, 4);
      std::memcpy(&key.bits[1], &p.y, 4);
      std::memcpy(&key.bits[2], &p.z, 4);
      auto it = seen.emplace(key, uint32_t(out_.positions.size()));
      if (it.second) out_.positions.push_back(p);
      welded_[i] = it.first->second;
    }
    out_.welded_vertices = out_.positions.size();
  }

  bool degenerate(const Node& n) const {
    return n.v[0] == n.v[1] || n.v[1] == n.v[2] || n.v[2] == n.v[0] ||
           !(triangle_area(out_.positions[n.v[0]], out_.positions[n.v[1]], out_.positions[n.v[2]]) > 0.0);
  }

  // Every too-long edge of the active triangles, with no midpoint vertex yet (~0u).
  void mark_long_edges(const std::vector<uint32_t>& active) {
    midpoints_.clear();
    for (uint32_t node : active) {
      const Node& n = nodes_[node];
      if (degenerate(n)) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = n.v[k], b = n.v[(k + 1) % 3];
        if (distance(out_.positions[a], out_.positions[b]) > max_edge_) midpoints_.emplace(edge_key(a, b), ~0u);
      }
    }
  }

  uint32_t midpoint(uint32_t a, uint32_t b) {
    uint32_t& m = midpoints_.at(edge_key(a, b));
    if (m == ~0u) {
      const Float3 &p = out_.positions[a], &q = out_.positions[b];
      m = uint32_t(out_.positions.size());
      out_.positions.push_back(Float3{float(0.5 * (double(p.x) + q.x)), float(0.5 * (double(p.y) + q.y)),
                                      float(0.5 * (double(p.z) + q.z))});
    }
    return m;
  }

  // A corner of a child: a vertex and its (u, v).
  struct Corner {
    uint32_t v;
    float u, w;
  };

  Corner corner(const Node& n, int k) const { return Corner{n.v[k], n.uv[k][0], n.uv[k][1]}; }

  Corner middle(const Corner& a, const Corner& b) {
    return Corner{midpoint(a.v, b.v), 0.5f * (a.u + b.u), 0.5f * (a.w + b.w)};
  }

  void add_child(uint32_t parent, const Corner& a, const Corner& b, const Corner& c) {
    Node child;
    const Corner* cs[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      child.v[k] = cs[k]->v;
      child.uv[k][0] = cs[k]->u;
      child.uv[k][1] = cs[k]->w;
    }
    child.source = nodes_[parent].source;
    nodes_.push_back(child);
  }

  void split(uint32_t node, std::vector<uint32_t>& next) {
    const Node n = nodes_[node];
    bool split_edge[3];
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      split_edge[k] = !degenerate(n) && midpoints_.count(edge_key(n.v[k], n.v[(k + 1) % 3])) > 0;
      count += split_edge[k];
    }
    if (count == 0) return;  // a final leaf
    // Rotate so that edge 0 (A, B) is the split one (1 split) or edge 2 (C, A) the unsplit one (2).
    int r = 0;
    for (int k = 0; k < 3; ++k)
      if ((count == 1 && split_edge[k]) || (count == 2 && !split_edge[(k + 2) % 3])) r = k;
    const Corner A = corner(n, r), B = corner(n, (r + 1) % 3), C = corner(n, (r + 2) % 3);
    const uint32_t first = uint32_t(nodes_.size());
    if (count == 1) {
      const Corner M = middle(A, B);
      add_child(node, A, M, C);
      add_child(node, M, B, C);
    } else if (count == 2) {
      const Corner Mab = middle(A, B), Mbc = middle(B, C);
      add_child(node, Mab, B, Mbc);
      // The quad A, Mab, Mbc, C along its shorter diagonal.
      const double d_a = distance(out_.positions[A.v], out_.positions[Mbc.v]);
      const double d_c = distance(out_.positions[Mab.v], out_.positions[C.v]);
      if (d_a <= d_c) {
        add_child(node, A, Mab, Mbc);
        add_child(node, A, Mbc, C);
      } else {
        add_child(node, A, Mab, C);
        add_child(node, Mab, Mbc, C);
      }
    } else {
      const Corner Mab = middle(A, B), Mbc = middle(B, C), Mca = middle(C, A);
      add_child(node, A, Mab, Mca);
      add_child(node, Mab, B, Mbc);
      add_child(node, Mca, Mbc, C);
      add_child(node, Mab, Mbc, Mca);
    }
    nodes_[node].first_child = first;
    nodes_[node].child_count = uint32_t(nodes_.size()) - first;
    leaves_ += nodes_[node].child_count - 1;
    if (leaves_ > kMaxRefinedTriangles)
      throw SettingError("max-edge", "refining to " + std::to_string(max_edge_) + " m would make more than " +
                                         std::to_string(kMaxRefinedTriangles) + " triangles; use a larger --max-edge");
    for (uint32_t c = first; c < nodes_.size(); ++c) next.push_back(c);
  }

  void write() {
    out_.tree.resize(2 * nodes_.size());
    out_.indices.reserve(3 * leaves_);
    out_.source.reserve(leaves_);
    for (size_t i = 0; i < nodes_.size(); ++i) {
      const Node& n = nodes_[i];
      uint32_t link = n.first_child;
      if (n.child_count == 0) {
        link = uint32_t(out_.source.size());
        out_.indices.insert(out_.indices.end(), {n.v[0], n.v[1], n.v[2]});
        out_.source.push_back(n.source);
      }
      out_.tree[2 * i] = float4{n.uv[0][0], n.uv[0][1], n.uv[1][0], n.uv[1][1]};
      out_.tree[2 * i + 1] = float4{n.uv[2][0], n.uv[2][1], PM_UINT_AS_FLOAT(link), PM_UINT_AS_FLOAT(n.child_count)};
    }
  }

  const Scene& scene_;
  const double max_edge_;
  RefinedMesh& out_;
  std::vector<uint32_t> welded_;
  std::vector<Node> nodes_;
  std::unordered_map<uint64_t, uint32_t> midpoints_;  // edges split this round -> midpoint vertex
  size_t leaves_ = 0;
};

}  // namespace

double estimate_refined_triangles(const Scene& scene, double max_edge) {
  // A triangle whose longest edge needs halving s times (2^s segments) becomes at most about
  // 4^s triangles: exact for the four-way splits of well-shaped triangles, more than enough for
  // thin ones (their short edges stop splitting early).
  double total = 0;
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    double longest = 0;
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, distance(scene.positions[scene.indices[3 * t + k]],
                                           scene.positions[scene.indices[3 * t + (k + 1) % 3]]));
    const double segments = longest > max_edge ? std::exp2(std::ceil(std::log2(longest / max_edge))) : 1.0;
    total += segments * segments;
  }
  return total;
}

RefinedMesh refine_mesh(const Scene& scene, double max_edge) {
  if (!(max_edge > 0) || !std::isfinite(max_edge))
    throw SettingError("max-edge", "must be a positive length in metres, got " + std::to_string(max_edge));
  RefinedMesh mesh;
  Refiner(scene, max_edge, mesh).run();
  return mesh;
}

}  // namespace pm
