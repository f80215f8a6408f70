// Shared pieces of the limits tests: a small game folder holding the synthetic one-room BSP, the
// q3map2 command line for it, and the checks every bounded outcome must pass.
#pragma once

#include "measured_run.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace q3::test {

// Peak resident memory any limits case may use: generous for a 256-unit room, far below what a
// runaway allocation would reach. The sanitizer build gets room for its shadow memory.
long limitsRssBoundMb();

// <game>/baseoa/maps/room.bsp: the synthetic room, its worldspawn carrying `worldspawnKeys`
// (e.g. "\"gridsize\" \"1 1 1\"\n"). Returns the BSP's path.
std::filesystem::path writeRoom(const std::filesystem::path& game, const std::string& worldspawnKeys = "");
// The same room with the world model's bounds widened to +-halfExtent on every axis (the grids are
// laid out over model 0's bounds), as <game>/baseoa/maps/wide.bsp.
std::filesystem::path writeWideRoom(const std::filesystem::path& game, float halfExtent,
                                    const std::string& worldspawnKeys = "");
// Writes raw bytes as <game>/baseoa/maps/<name>; returns the path.
std::filesystem::path writeMapFile(const std::filesystem::path& game, const std::string& name,
                                   const std::vector<uint8_t>& bytes);

// q3map2 with the game folder as base path: q3map2 [common...] -fs_basepath game -fs_game baseoa
// stage... bsp.
std::vector<std::string> q3map2Command(const std::filesystem::path& game, const std::vector<std::string>& common,
                                       const std::vector<std::string>& stage, const std::filesystem::path& bsp);

// Runs a q3map2 command, measured.
MeasuredRun runQ3map2(const std::vector<std::string>& argv, double seconds = 120.0);

// The run ended by itself (no signal, no time-out), below `rssBoundMb` of peak memory
// (limitsRssBoundMb() when 0), and never reported an allocation failure.
void expectBounded(const MeasuredRun& run, long rssBoundMb = 0);
// Bounded, exit code `exitCode`, and exactly one "ERROR:" line, which contains `needle`.
void expectOneLineError(const MeasuredRun& run, int exitCode, const std::string& needle);
// Bounded, exit code 0, and a warning (or info line) containing `needle` when it is not empty.
void expectSuccess(const MeasuredRun& run, const std::string& needle = "", long rssBoundMb = 0);

}  // namespace q3::test
