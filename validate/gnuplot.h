#pragma once
// The validations' plots are gnuplot scripts written beside their CSV files,
// so anyone can rerun or restyle them; the PNG is made where gnuplot is
// installed (scripts/bootstrap installs it).
#include <filesystem>

namespace zenith::validate {

/// Runs gnuplot on `script` in the script's directory. False when gnuplot is
/// not installed or fails on it (its messages are dropped: the caller says
/// where the script is).
bool run_gnuplot(const std::filesystem::path& script);

}  // namespace zenith::validate
