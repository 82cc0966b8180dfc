#include "anisodyn/neighbors/skin_list.hpp"

#include <algorithm>
#include <utility>

namespace anisodyn {

void SkinList::configure(std::vector<double> half_skin, std::vector<char> listed) {
  half_skin_ = std::move(half_skin);
  listed_ = std::move(listed);
  any_ = std::any_of(half_skin_.begin(), half_skin_.end(), [](double t) { return t > 0.0; });
  clear();
}

void SkinList::clear() {
  reference_r_.clear();
  reference_R_.clear();
  referenced_.clear();
  neighbors_.clear();
}

void SkinList::grow_to(std::size_t n) {
  if (reference_r_.size() >= n) return;
  reference_r_.resize(n, Vec3::Zero());
  reference_R_.resize(n, Mat3::Identity());
  referenced_.resize(n, 0);
  neighbors_.resize(n);
}

void SkinList::reset_reference(std::int32_t i, const Vec3& r, const Mat3& R) {
  const auto ui = static_cast<std::size_t>(i);
  grow_to(ui + 1);
  for (std::int32_t j : neighbors_[ui]) {
    auto& other = neighbors_[static_cast<std::size_t>(j)];
    other.erase(std::find(other.begin(), other.end(), i));
  }
  neighbors_[ui].clear();
  reference_r_[ui] = r;
  reference_R_[ui] = R;
  referenced_[ui] = 1;
  ++resets_;
}

void SkinList::link(std::int32_t i, std::int32_t j) {
  neighbors_[static_cast<std::size_t>(i)].push_back(j);
  neighbors_[static_cast<std::size_t>(j)].push_back(i);
}

}  // namespace anisodyn
