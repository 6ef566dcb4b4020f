#pragma once
// Each subcommand registers its options and its action on the top-level app.

#include <CLI/CLI.hpp>

#include "pena/io/log_source.hpp"

namespace pena::cli {

// --carmen-sweep and --carmen-interlace, for the tools that run the odometry chain
// (docs/formats.md, "Sweep time").
void AddCarmenSweepOptions(CLI::App& command, io::ReadOptions& read);

void AddInfoCommand(CLI::App& app);      // pena info FILE
void AddExportCommand(CLI::App& app);    // pena export --log LOG --carmen|--csm OUT
void AddEvalCommand(CLI::App& app);      // pena eval --trajectory T (--relations R | --truth T)
void AddSimulateCommand(CLI::App& app);  // pena simulate --scenario NAME|FILE --seed N --out DIR
void AddOdometryCommand(CLI::App& app);  // pena odometry --log LOG --out DIR
void AddMapCommand(CLI::App& app);       // pena map --log LOG [--trajectory T] --out DIR
void AddLocaliseCommand(CLI::App& app);  // pena localise --log LOG --map PLAN --out DIR
void AddReportCommand(CLI::App& app);    // pena report --mission M --run R [--out DIR]

}  // namespace pena::cli
