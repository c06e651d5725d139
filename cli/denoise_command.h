#pragma once
/// `nenrin denoise IN.exr -o OUT.exr [--png P.png]`: a rendered EXR denoised by the AOV-guided
/// à-trous filter (docs/denoise.md), e.g. a split render after `nenrin merge`.

#include <CLI/CLI.hpp>

namespace nenrin {

void addDenoiseCommand(CLI::App& app);

}  // namespace nenrin
