// The approximate cutter's tree of cells (cut_tree.hpp).
#include "mesh/cut_tree.hpp"

#include <algorithm>
#include <limits>

#include "geometry/aabb.hpp"
#include "mesh/hull_polyhedron.hpp"
#include "mesh/part_components.hpp"
#include "support/parallel.hpp"

namespace tem::approximate {

CutTree::CutTree(Leaf root, const Context& context, int max_blocks, Real enough,
                 Real distance_goal, Real touching, Real smallest_gain)
    : nodes_(1),
      context_(context),
      max_blocks_(max_blocks),
      enough_(enough),
      distance_goal_(distance_goal),
      touching_(touching),
      smallest_gain_(smallest_gain) {
  nodes_[0].leaf = std::move(root);
}

std::optional<Split>& CutTree::known_split(int n, int room) {
  Node& node = nodes_[n];
  if (!node.next_known || (node.next && static_cast<int>(node.next->children.size()) > room)) {
    context_.for_distance = false;
    context_.room = room;
    node.next = split(node.leaf, context_);
    node.next_known = true;
    if (!node.next) node.leaf.final = true;
  }
  return node.next;
}

void CutTree::touched(int n) {
  for (; n >= 0; n = nodes_[n].parent) nodes_[n].moved_below = true;
}

void CutTree::apply(int n, Split cut) {
  touched(n);
  for (Leaf& leaf : cut.children) {
    Node child;
    child.leaf = std::move(leaf);
    child.parent = n;
    nodes_[n].children.push_back(static_cast<int>(nodes_.size()));
    nodes_.push_back(std::move(child));
  }
  leaf_count_ += static_cast<int>(nodes_[n].children.size()) - 1;
  nodes_[n].plane = cut.plane;
  nodes_[n].first_side_pieces = cut.first_side_pieces;
  nodes_[n].next.reset();
  nodes_[n].next_known = false;
}

void CutTree::start_with_shells(Real smallest_volume) {
  const Real gap = kWeld * radius_about_mean(nodes_[0].leaf.part.points);
  auto shells = separate_groups(nodes_[0].leaf.part, smallest_volume, gap);
  if (shells.size() > 1 && static_cast<int>(shells.size()) <= max_blocks_)
    if (auto children = leaves_of(std::move(shells), context_))
      apply(0, split_into(nodes_[0].leaf.hull_volume, std::move(*children)));
}

void CutTree::grow(int up_to) {
  if (up_to < 0) up_to = max_blocks_;
  while (leaf_count_ < up_to) {
    const int room = max_blocks_ - leaf_count_ + 1;
    int worst = -1;
    for (size_t i = 0; i < nodes_.size(); ++i)
      if (nodes_[i].is_leaf() && !nodes_[i].leaf.final &&
          nodes_[i].leaf.distance > distance_goal_ &&
          (worst < 0 || nodes_[i].leaf.distance > nodes_[worst].leaf.distance))
        worst = static_cast<int>(i);
    if (worst >= 0) {
      context_.for_distance = true;
      context_.room = room;
      auto cut = split(nodes_[worst].leaf, context_);
      if (cut) apply(worst, std::move(*cut));
      else nodes_[worst].leaf.final = true;
      continue;
    }
    for (size_t i = 0; i < nodes_.size(); ++i) {
      const Leaf& leaf = nodes_[i].leaf;
      if (nodes_[i].is_leaf() && !leaf.final && leaf.concavity() > enough_ &&
          (worst < 0 || leaf.concavity() > nodes_[worst].leaf.concavity()))
        worst = static_cast<int>(i);
    }
    if (worst < 0) break;
    auto& cut = known_split(worst, room);
    if (cut) apply(worst, std::move(*cut));
  }
}

int CutTree::cheapest_pair_merge(Real below, std::optional<Leaf>& merged) {
  const size_t first = leaf_pairs_.size();
  for (size_t b = paired_; b < nodes_.size(); ++b) {
    if (!nodes_[b].is_leaf()) continue;
    const Aabb box_b = Aabb::around(nodes_[b].leaf.block.points);
    for (size_t a = 0; a < b; ++a)
      if (nodes_[a].is_leaf() && (nodes_[a].parent < 0 || nodes_[a].parent != nodes_[b].parent) &&
          Aabb::around(nodes_[a].leaf.block.points).within(box_b, touching_))
        leaf_pairs_.push_back({static_cast<int>(a), static_cast<int>(b)});
  }
  paired_ = nodes_.size();
  parallel_for(
      static_cast<long long>(leaf_pairs_.size() - first), 1,
      [&](long long i) {
        LeafPair& p = leaf_pairs_[first + i];
        p.cost = merge_cost(nodes_[p.a].leaf, nodes_[p.b].leaf);
      },
      true);
  std::vector<int> order;
  for (size_t i = 0; i < leaf_pairs_.size(); ++i) {
    const LeafPair& p = leaf_pairs_[i];
    if (!p.refused && p.cost < below && nodes_[p.a].is_leaf() && nodes_[p.b].is_leaf())
      order.push_back(static_cast<int>(i));
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](int x, int y) { return leaf_pairs_[x].cost < leaf_pairs_[y].cost; });
  for (int i : order) {
    LeafPair& p = leaf_pairs_[i];
    std::vector<const Leaf*> others;
    for (size_t k = 0; k < nodes_.size(); ++k)
      if (nodes_[k].is_leaf() && static_cast<int>(k) != p.a && static_cast<int>(k) != p.b)
        others.push_back(&nodes_[k].leaf);
    merged = merged_leaf(nodes_[p.a].leaf, nodes_[p.b].leaf, others, distance_goal_, touching_,
                         context_);
    if (merged) return i;
    p.refused = true;
  }
  return -1;
}

void CutTree::improve() {
  for (int round = 0; round < 4 * max_blocks_; ++round) {
    // The node whose children merge back at least cost...
    int merge = -1;
    Real cost = std::numeric_limits<Real>::infinity();
    for (size_t i = 0; i < nodes_.size(); ++i) {
      const Node& node = nodes_[i];
      if (!node.alive || node.children.empty() ||
          !std::all_of(node.children.begin(), node.children.end(),
                       [&](int c) { return nodes_[c].is_leaf(); }))
        continue;
      settle(static_cast<int>(i));
      if (node.leaf.distance > distance_goal_) continue;
      Real c = node.leaf.hull_volume;
      for (int child : node.children) c -= nodes_[child].leaf.hull_volume;
      if (merge < 0 || c < cost) {
        merge = static_cast<int>(i);
        cost = c;
      }
    }
    // ... or two neighbours for less.
    std::optional<Leaf> pair_leaf;
    const int pair = cheapest_pair_merge(cost, pair_leaf);
    int pair_a = -1, pair_b = -1;
    if (pair >= 0) {
      pair_a = leaf_pairs_[pair].a;
      pair_b = leaf_pairs_[pair].b;
      cost = leaf_pairs_[pair].cost;
      merge = -1;
    } else if (merge < 0) {
      break;
    }
    const int room = max_blocks_ - leaf_count_ +
                     (pair >= 0 ? 2 : static_cast<int>(nodes_[merge].children.size()));
    // A cut gains at most the leaf's concavity (each child's hull holds the child), so leaves
    // are looked at by falling concavity until none can beat the best gain found: cuts are
    // found for few of them, and the choice is the same as if for all.
    std::vector<int> order;
    for (size_t i = 0; i < nodes_.size(); ++i) {
      const int n = static_cast<int>(i);
      if (nodes_[i].is_leaf() && (merge < 0 || nodes_[i].parent != merge) && n != pair_a &&
          n != pair_b && !nodes_[i].leaf.final && nodes_[i].leaf.concavity() > enough_)
        order.push_back(n);
    }
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return nodes_[a].leaf.concavity() > nodes_[b].leaf.concavity();
    });
    int best = -1;
    for (int i : order) {
      if (!(nodes_[i].leaf.concavity() > cost + context_.tie) ||
          (best >= 0 && !(nodes_[i].leaf.concavity() > nodes_[best].next->gain)))
        break;
      const auto& cut = known_split(i, room);
      if (!cut) continue;
      bool strays = false;
      for (const Leaf& child : cut->children) strays |= child.distance > distance_goal_;
      if (strays && nodes_[i].leaf.distance <= distance_goal_) continue;
      if (best < 0 || cut->gain > nodes_[best].next->gain) best = i;
    }
    if (best < 0 || !(nodes_[best].next->gain > cost + context_.tie)) break;
    if (pair >= 0) {
      nodes_[pair_a].alive = nodes_[pair_b].alive = false;
      touched(nodes_[pair_a].parent);
      touched(nodes_[pair_b].parent);
      Node merged;
      merged.leaf = std::move(*pair_leaf);
      nodes_.push_back(std::move(merged));
      --leaf_count_;
    } else {
      Node& parent = nodes_[merge];
      Split back;
      for (int child : parent.children) {
        back.children.push_back(std::move(nodes_[child].leaf));
        nodes_[child].alive = false;
      }
      back.gain = cost;
      back.plane = parent.plane;
      back.first_side_pieces = parent.first_side_pieces;
      leaf_count_ -= static_cast<int>(parent.children.size()) - 1;
      parent.children.clear();
      touched(merge);
      parent.plane.reset();
      parent.next = std::move(back);
      parent.next_known = true;
    }
    Split cut = std::move(*nodes_[best].next);
    apply(best, std::move(cut));
    grow();
  }
}

bool CutTree::recut_last_cuts() {
  context_.lookahead = 0;
  bool recut = false;
  for (size_t i = 0, count = nodes_.size(); i < count; ++i) {
    const Node& node = nodes_[i];
    if (!node.alive || node.children.size() != 2 ||
        !std::all_of(node.children.begin(), node.children.end(),
                     [&](int c) { return nodes_[c].is_leaf(); }))
      continue;
    Real hulls = 0, strays = distance_goal_;
    for (int c : node.children) {
      hulls += nodes_[c].leaf.hull_volume;
      strays = std::max(strays, nodes_[c].leaf.distance);
    }
    context_.for_distance = false;
    context_.room = 2;
    auto again = split(node.leaf, context_);
    if (!again || again->children.size() != 2) continue;
    Real new_hulls = 0, new_strays = 0;
    for (const Leaf& child : again->children) {
      new_hulls += child.hull_volume;
      new_strays = std::max(new_strays, child.distance);
    }
    if (!(new_hulls < hulls - context_.tie) || new_strays > strays) continue;
    nodes_[i].plane = again->plane;
    nodes_[i].first_side_pieces = again->first_side_pieces;
    for (int k = 0; k < 2; ++k) {
      Node& child = nodes_[node.children[k]];
      child.leaf = std::move(again->children[k]);
      child.next.reset();
      child.next_known = false;
    }
    touched(static_cast<int>(i));
    recut = true;
  }
  if (recut) {  // the pairs' costs and verdicts were the old children's
    leaf_pairs_.clear();
    paired_ = 0;
  }
  for (Node& node : nodes_)
    if (node.is_leaf()) {
      node.next.reset();
      node.next_known = false;
    }
  return recut;
}

std::vector<Leaf> CutTree::take_leaves() {
  std::vector<Leaf> leaves;
  for (Node& node : nodes_)
    if (node.is_leaf()) leaves.push_back(std::move(node.leaf));
  return leaves;
}

}  // namespace tem::approximate
