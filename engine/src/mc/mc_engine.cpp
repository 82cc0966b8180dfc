#include "anisodyn/mc/mc_engine.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/quaternion.hpp"

namespace anisodyn {

namespace {
std::string describe_pair(const State& s, std::int32_t i, std::int32_t j) {
  return "particles " + std::to_string(s.particles.id[static_cast<std::size_t>(i)]) + " and " +
         std::to_string(s.particles.id[static_cast<std::size_t>(j)]) + " overlap";
}
}  // namespace

McEngine::McEngine(State& state, const RngState& rng) : state_(state), rng_(rng), overlap_(state) {
  if (auto pair = overlap_.first_overlap())
    throw InputError("", "", "overlapping configuration: " + describe_pair(state, pair->first, pair->second));
  const std::size_t ns = state.species.size();
  moves_.translate.resize(ns);
  moves_.rotate.resize(ns);
  for (std::size_t s = 0; s < ns; ++s) {
    // Start at a tenth of the smallest body dimension; tuning takes it from there.
    moves_.translate[s] = 0.1 * 2.0 * state.species[s].shape.inscribed_radius();
    moves_.rotate[s] = 0.1;
  }
  counters_.reset(ns);
  unseen_moves_.assign(ns, 0);
}

void McEngine::restore(const RngState& rng, const MoveCounters& counters, const MoveSizes& moves, int volume_moves_owed) {
  rng_ = Rng(rng);
  counters_ = counters;
  moves_ = moves;
  volume_moves_owed_ = volume_moves_owed;
}

void McEngine::set_pressure(std::optional<double> beta_pressure, BoxMoves moves) {
  beta_pressure_ = beta_pressure;
  box_moves_ = moves;
}

void McEngine::set_domain_sweeps(bool on) {
  if (on && !domains_) domains_ = std::make_unique<DomainSweep>();
  if (!on) {
    settle_volume_moves();
    refresh_overlap();
    domains_.reset();
  }
}

void McEngine::refresh_overlap() {
  if (overlap_stale_) update_overlap();
}

void McEngine::update_overlap() {
  overlap_.refresh(state_, unseen_moves_);
  std::fill(unseen_moves_.begin(), unseen_moves_.end(), 0);
  overlap_stale_ = false;
}

void McEngine::note_unseen_moves(const MoveCounters& made) {
  for (std::size_t s = 0; s < unseen_moves_.size(); ++s) unseen_moves_[s] += made.translate_accepted[s] + made.rotate_accepted[s];
}

int McEngine::domain_cycles(int wanted) {
  const MoveCounters before = counters_;
  const int done = domains_->cycles(state_, rng_, wanted, moves_, field_, removing_overlaps_, counters_);
  note_unseen_moves(counters_.since(before));
  overlap_stale_ = true;
  // Volume moves wait for the cut's end: a box change would make every domain copy again, and
  // would end the batch of the cut's cycles. Each cycle keeps the distribution at fixed volume,
  // each volume move keeps it too, and when the moves are made does not depend on the
  // configuration, so their sequence keeps it as well.
  if (beta_pressure_) volume_moves_owed_ += done;
  if (!domains_->cut()) settle_volume_moves();
  return done;
}

void McEngine::settle_volume_moves() {
  // Made under the pressure in force at the cut's end; they lapse if a constant-volume phase has
  // begun within the cut.
  if (!beta_pressure_) volume_moves_owed_ = 0;
  for (; volume_moves_owed_ > 0; --volume_moves_owed_) volume_move();
}

void McEngine::box_rescaled() {
  if (domains_) domains_->invalidate();
}

void McEngine::positions_rescaled() {
  // Domain sweeps search copies of their slabs, so the whole configuration's structures are
  // needed only by the next compression's overlap check (or a caller of overlap()): refresh them
  // then. The sequential sweep's next trial needs them now.
  if (domains_) overlap_stale_ = true;
  else update_overlap();
}

void McEngine::cycle() {
  const std::size_t n = state_.particles.size();
  if (domains_) {
    domain_cycles(1);
    return;
  }
  refresh_overlap();
  if (!beta_pressure_) {
    for (std::size_t t = 0; t < n; ++t) particle_move();
    return;
  }
  // N + 1 moves, each a volume move with probability 1/(N + 1): one volume move per cycle on average.
  for (std::size_t t = 0; t <= n; ++t) {
    if (rng_.index(n + 1) == 0) volume_move();
    else particle_move();
  }
}

int McEngine::cycles(int wanted) {
  if (!domains_) {
    cycle();
    return 1;
  }
  return domain_cycles(wanted);
}

void McEngine::particle_move() {
  const auto i = static_cast<std::int32_t>(rng_.index(state_.particles.size()));
  TrialMove{state_, overlap_, rng_, counters_, moves_, field_, removing_overlaps_, nullptr}.attempt(i);
}

void McEngine::rescale_allowing_overlaps(double volume) {
  const Vec3 old_edges = state_.box.edges();
  const Vec3 new_edges = old_edges * std::cbrt(volume / state_.box.volume());
  rescale_positions(new_edges.cwiseQuotient(old_edges));
  state_.box.set_edges(new_edges);
  positions_rescaled();
  box_rescaled();
}

void McEngine::rescale_positions(const Vec3& factor) {
  Particles& p = state_.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.x[i] *= factor.x();
    p.y[i] *= factor.y();
    p.z[i] *= factor.z();
  }
}

bool McEngine::any_overlap_after_rescale(const Vec3& new_edges) {
  const Vec3 old_edges = state_.box.edges();
  Particles& p = state_.particles;
  // Keep the old positions: scaling back by the inverse factor is off in the last bits.
  saved_x_ = p.x;
  saved_y_ = p.y;
  saved_z_ = p.z;
  rescale_positions(new_edges.cwiseQuotient(old_edges));
  state_.box.set_edges(new_edges);
  update_overlap();
  const std::optional<std::int32_t> witness = overlap_.overlapping_particle(suspects_);
  if (!witness) return false;
  suspect(*witness);
  p.x.swap(saved_x_);
  p.y.swap(saved_y_);
  p.z.swap(saved_z_);
  state_.box.set_edges(old_edges);
  positions_rescaled();
  return true;
}

void McEngine::suspect(std::int32_t i) {
  const auto known = std::find(suspects_.begin(), suspects_.end(), i);
  if (known != suspects_.end()) suspects_.erase(known);
  else if (suspects_.size() == kSuspects) suspects_.pop_back();
  suspects_.insert(suspects_.begin(), i);
}

void McEngine::volume_move() {
  counters_.volume_tried++;
  const Vec3 old_edges = state_.box.edges();
  const double old_volume = state_.box.volume();
  const double dlnv = rng_.uniform(-moves_.log_volume, moves_.log_volume);
  Vec3 new_edges = old_edges;
  bool radial = true;  // isotropic scaling: expansion cannot create overlaps of centrosymmetric convex bodies
  if (box_moves_ == BoxMoves::Isotropic) {
    new_edges *= std::exp(dlnv / 3.0);
  } else {
    new_edges[static_cast<int>(rng_.index(3))] *= std::exp(dlnv);
    radial = false;
  }
  const double new_volume = new_edges.prod();
  // Minimum image needs every edge ≥ 2 × the largest cut-off.
  if (new_edges.minCoeff() < 2.0 * overlap_.max_cutoff()) return;
  const double n = static_cast<double>(state_.particles.size());
  const double log_acc = -*beta_pressure_ * (new_volume - old_volume) + (n + 1.0) * std::log(new_volume / old_volume);
  if (log_acc < 0.0 && rng_.uniform() >= std::exp(log_acc)) return;
  if (radial && new_volume >= old_volume) {
    rescale_positions(new_edges.cwiseQuotient(old_edges));
    state_.box.set_edges(new_edges);
    positions_rescaled();
  } else if (any_overlap_after_rescale(new_edges)) {
    return;
  }
  box_rescaled();
  counters_.volume_accepted++;
}

bool McEngine::try_rescale(double volume) {
  const Vec3 old_edges = state_.box.edges();
  const Vec3 new_edges = old_edges * std::cbrt(volume / state_.box.volume());
  if (new_edges.minCoeff() < 2.0 * overlap_.max_cutoff()) return false;
  if (volume >= state_.box.volume()) {
    rescale_positions(new_edges.cwiseQuotient(old_edges));
    state_.box.set_edges(new_edges);
    positions_rescaled();
    box_rescaled();
    return true;
  }
  if (any_overlap_after_rescale(new_edges)) return false;
  box_rescaled();
  return true;
}

void McEngine::tune(double target, const MoveCounters& w) {
  auto scale = [target](double acceptance) { return std::clamp(acceptance / target, 0.5, 1.5); };
  const double max_translate = 0.25 * state_.box.shortest_edge();
  for (std::size_t s = 0; s < state_.species.size(); ++s) {
    if (w.translate_tried[s] > 0)
      moves_.translate[s] = std::min(max_translate,
                                     moves_.translate[s] * scale(MoveCounters::ratio(w.translate_accepted[s], w.translate_tried[s])));
    if (w.rotate_tried[s] > 0)
      moves_.rotate[s] = std::min(M_PI, moves_.rotate[s] * scale(MoveCounters::ratio(w.rotate_accepted[s], w.rotate_tried[s])));
  }
  if (w.volume_tried > 0)
    moves_.log_volume = std::min(0.5, moves_.log_volume * scale(MoveCounters::ratio(w.volume_accepted, w.volume_tried)));
}

double McEngine::field_energy() const {
  if (!field_.active()) return 0.0;
  double u = 0.0;
  for (std::size_t i = 0; i < state_.particles.size(); ++i) {
    if (state_.species[static_cast<std::size_t>(state_.particles.species[i])].shape.is_anisotropic())
      u += field_.energy(state_.particles.orientation(i).toRotationMatrix());
  }
  return u;
}

}  // namespace anisodyn
