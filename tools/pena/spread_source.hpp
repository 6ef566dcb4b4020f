#pragma once
// The log as `pena localise`'s chain (localisation::LocalisationChain, which has no stride
// spreading of its own) takes it: a person's strides spread over the scans taken during them
// (dead_reckoning::StrideInterpolator, docs/dead-reckoning.md); other logs as read. The entity
// pipeline, which the other subcommands run, spreads them itself.

#include <filesystem>
#include <memory>

#include "pena/dead_reckoning/human_dead_reckoning.hpp"
#include "pena/dead_reckoning/stride_interpolator.hpp"
#include "pena/io/log_source.hpp"

namespace pena::cli {

// Opens the log (io::OpenLog) and, for a human entity with stride_interpolation enabled, spreads
// its strides. Records are held until the report that ends their stride (at most max_hold_s).
std::unique_ptr<io::LogSource> OpenChainLog(
    const std::filesystem::path& path, const io::ReadOptions& read,
    const dead_reckoning::HumanDeadReckoningOptions& options);

// What the spreading did so far, if `source` (from OpenChainLog) spreads strides; else nullptr.
const dead_reckoning::StrideInterpolationCounts* StrideSpreadingCounts(const io::LogSource& source);

}  // namespace pena::cli
