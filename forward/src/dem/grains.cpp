#include "sedwave/forward/dem/grains.hpp"

#include <stdexcept>

namespace sedwave::forward::dem {

void GrainArrays::push_common(const Grain& g) {
  position.push_back(g.position);
  velocity.push_back(g.velocity);
  if (rotation_) angular_velocity.push_back(g.angular_velocity);
  radius.push_back(g.radius);
  mass.push_back(g.mass);
  inv_mass.push_back(g.body == kFreeBody ? 1.0 / g.mass : 0.0);
  id.push_back(g.id);
  group.push_back(g.group);
  body.push_back(g.body);
}

void GrainArrays::push_local(const Grain& g) {
  if (n_ghost() != 0) throw std::logic_error("GrainArrays::push_local with ghosts present");
  push_common(g);
  force.push_back(g.force);
  if (rotation_) torque.push_back(g.torque);
  ++n_local_;
}

void GrainArrays::push_ghost(const Grain& g) {
  push_common(g);
  force.emplace_back();
  if (rotation_) torque.emplace_back();
}

void GrainArrays::clear_ghosts() {
  const std::size_t n = n_local_;
  position.resize(n);
  velocity.resize(n);
  if (rotation_) {
    angular_velocity.resize(n);
    torque.resize(n);
  }
  force.resize(n);
  radius.resize(n);
  mass.resize(n);
  inv_mass.resize(n);
  id.resize(n);
  group.resize(n);
  body.resize(n);
}

Grain GrainArrays::grain(std::size_t i) const {
  Grain g;
  g.id = id[i];
  g.group = group[i];
  g.body = body[i];
  g.radius = radius[i];
  g.mass = mass[i];
  g.position = position[i];
  g.velocity = velocity[i];
  g.force = force[i];
  if (rotation_) {
    g.angular_velocity = angular_velocity[i];
    g.torque = torque[i];
  }
  return g;
}

namespace {
template <typename T>
void keep_entries(std::vector<T>& v, std::span<const std::uint8_t> keep) {
  std::size_t out = 0;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) v[out++] = v[i];
  v.resize(out);
}
template <typename T>
void permute_entries(std::vector<T>& v, std::span<const std::uint32_t> order) {
  std::vector<T> tmp(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) tmp[k] = v[order[k]];
  v.swap(tmp);
}
}  // namespace

void GrainArrays::keep_local(std::span<const std::uint8_t> keep) {
  if (n_ghost() != 0 || keep.size() != n_local_)
    throw std::logic_error("GrainArrays::keep_local needs one flag per local grain and no ghosts");
  keep_entries(position, keep);
  keep_entries(velocity, keep);
  keep_entries(force, keep);
  if (rotation_) {
    keep_entries(angular_velocity, keep);
    keep_entries(torque, keep);
  }
  keep_entries(radius, keep);
  keep_entries(mass, keep);
  keep_entries(inv_mass, keep);
  keep_entries(id, keep);
  keep_entries(group, keep);
  keep_entries(body, keep);
  n_local_ = id.size();
}

void GrainArrays::permute_local(std::span<const std::uint32_t> order) {
  if (n_ghost() != 0 || order.size() != n_local_)
    throw std::logic_error("GrainArrays::permute_local needs a full permutation and no ghosts");
  permute_entries(position, order);
  permute_entries(velocity, order);
  permute_entries(force, order);
  if (rotation_) {
    permute_entries(angular_velocity, order);
    permute_entries(torque, order);
  }
  permute_entries(radius, order);
  permute_entries(mass, order);
  permute_entries(inv_mass, order);
  permute_entries(id, order);
  permute_entries(group, order);
  permute_entries(body, order);
}

}  // namespace sedwave::forward::dem
