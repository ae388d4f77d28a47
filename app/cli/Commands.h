#pragma once

#include <CLI/CLI.hpp>

// Each boneless-cli subcommand lives in its own file and registers itself here.
void registerEvalCommand(CLI::App& app);
void registerDemoCommand(CLI::App& app);
void registerMapCommand(CLI::App& app);
void registerSolveCommand(CLI::App& app);
void registerInspectCommand(CLI::App& app);
void registerBatchCommand(CLI::App& app);
