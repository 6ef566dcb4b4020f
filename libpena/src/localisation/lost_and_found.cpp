#include "pena/localisation/lost_and_found.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pena/options_check.hpp"

namespace pena::localisation {
namespace {

void Require(bool ok, const std::string& field, const std::string& rule, double value) {
  RequireOption(ok, "lost_and_found", field, rule, value);
}

void Validate(const LostAndFoundOptions& o) {
  Require(o.lost_after_rounds >= 1, "lost_after_rounds", ">= 1", o.lost_after_rounds);
  Require(o.lost_explained_fraction >= 0.0 && o.lost_explained_fraction <= 1.0, "lost_explained_fraction",
          "in [0, 1]", o.lost_explained_fraction);
  Require(o.lost_sigma_m > 0.0 && std::isfinite(o.lost_sigma_m), "lost_sigma_m", "> 0 m", o.lost_sigma_m);
  Require(o.region_start_m > 0.0 && std::isfinite(o.region_start_m), "region_start_m", "> 0 m", o.region_start_m);
  Require(o.region_growth >= 1.0 && std::isfinite(o.region_growth), "region_growth", ">= 1", o.region_growth);
  Require(o.search_every_m >= 0.0 && std::isfinite(o.search_every_m), "search_every_m", ">= 0 m", o.search_every_m);
  Require(o.max_candidates >= 1, "max_candidates", ">= 1", o.max_candidates);
  Require(o.confirm_keyframes >= 1, "confirm_keyframes", ">= 1 keyframes", o.confirm_keyframes);
  Require(o.found_explained_fraction > 0.0 && o.found_explained_fraction <= 1.0, "found_explained_fraction",
          "in (0, 1]", o.found_explained_fraction);
  Require(o.found_margin >= 0.0 && o.found_margin <= 1.0, "found_margin", "in [0, 1]", o.found_margin);
}

// Two confirmed places closer in evidence than this are a tie: the walk goes on until one leads.
constexpr double kTieAgreement = 0.05;

}  // namespace

LostAndFound::LostAndFound(const LostAndFoundOptions& options, const GlobalLocaliser& global)
    : options_(options), global_(&global) {
  Validate(options_);
}

LostStep LostAndFound::Update(const sensors::LaserScan& scan, const std::optional<MapCorrection>& round,
                              const geometry::Pose2& odom_from_body, const geometry::Pose2& map_from_body,
                              double sigma_since_good_m) {
  LostStep step;
  if (last_odom_) walked_m_ += std::hypot(odom_from_body.x_m - last_odom_->x_m, odom_from_body.y_m - last_odom_->y_m);
  last_odom_ = odom_from_body;
  if (!options_.enabled) return step;
  if (!lost_) {
    if (!round || round->accepted) {
      if (round) bad_rounds_ = 0;
      return step;
    }
    // A failed round alone is no evidence: the match may be weak where the plan still explains
    // the scan. A round failing where the plan explains little of it is.
    // Outside the plan's box the plan is not expected to explain the scan: the entity may have
    // walked off the plan (an annex it does not draw), and plan rounds take it back on return.
    if (!global_->Inside(map_from_body)) {
      bad_rounds_ = 0;
      return step;
    }
    step.explained = global_->Agreement(scan, map_from_body).fraction();
    bad_rounds_ = step.explained < options_.lost_explained_fraction ? bad_rounds_ + 1 : 0;
    if (bad_rounds_ < options_.lost_after_rounds && sigma_since_good_m <= options_.lost_sigma_m) return step;
    lost_ = true;
    step.became_lost = true;
    radius_m_ = options_.region_start_m;
    search_due_ = true;
    candidates_.clear();
  } else {
    step.explained = global_->Agreement(scan, map_from_body).fraction();
  }
  // A plan round matched on its own where the plan explains the scan: found where it is.
  if (round && round->accepted && step.explained >= options_.found_explained_fraction) {
    step.found_by_round = true;
  } else if (const auto place = Confirm(scan, odom_from_body, step.explained)) {
    step.found = place;
  }
  if (step.found || step.found_by_round) {
    lost_ = false;
    bad_rounds_ = 0;
    candidates_.clear();
    return step;
  }
  if (search_due_ || walked_m_ >= options_.search_every_m) Search(scan, odom_from_body, map_from_body, step);
  step.lost = true;
  return step;
}

void LostAndFound::Search(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body,
                          const geometry::Pose2& map_from_body, LostStep& step) {
  const SearchRegion region{Eigen::Vector2d(map_from_body.x_m, map_from_body.y_m), radius_m_};
  const bool whole = radius_m_ <= 0.0 || global_->Covers(region);
  const GlobalResult result =
      global_->Localise(scan, options_.max_candidates, std::nullopt, whole ? std::nullopt : std::optional(region));
  step.searched_radius_m = whole ? 0.0 : radius_m_;
  for (const PoseHypothesis& h : result.hypotheses) {
    if (h.agreement < options_.found_explained_fraction || h.agreement < step.explained + options_.found_margin) continue;
    const bool known = std::any_of(candidates_.begin(), candidates_.end(), [&](const Candidate& c) {
      return SamePlace(c.map_from_body, h.map_from_body);
    });
    if (!known) candidates_.push_back({h.map_from_body, odom_from_body, 1, h.agreement});
  }
  radius_m_ = whole ? 0.0 : radius_m_ * options_.region_growth;
  walked_m_ = 0.0;
  search_due_ = false;
}

std::optional<geometry::Pose2> LostAndFound::Confirm(const sensors::LaserScan& scan,
                                                     const geometry::Pose2& odom_from_body, double explained_here) {
  std::vector<Candidate> kept;
  for (const Candidate& c : candidates_) {
    // The candidate moved as the odometry moved since it was fitted, then fitted again.
    const geometry::Pose2 predicted =
        geometry::Compose(c.map_from_body, geometry::Between(c.odom_from_body, odom_from_body));
    const PoseHypothesis fitted = global_->Verify(scan, predicted);
    if (fitted.agreement < options_.found_explained_fraction ||
        fitted.agreement < explained_here + options_.found_margin) {
      continue;
    }
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const Candidate& k) {
      return SamePlace(k.map_from_body, fitted.map_from_body);
    });
    if (!duplicate) kept.push_back({fitted.map_from_body, odom_from_body, c.confirmations + 1, fitted.agreement});
  }
  candidates_ = std::move(kept);
  const auto best = std::max_element(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
    return a.agreement < b.agreement;
  });
  if (best == candidates_.end() || best->confirmations < options_.confirm_keyframes) return std::nullopt;
  for (const Candidate& other : candidates_) {
    if (&other != &*best && best->agreement - other.agreement < kTieAgreement) return std::nullopt;  // a tie
  }
  return best->map_from_body;
}

}  // namespace pena::localisation
