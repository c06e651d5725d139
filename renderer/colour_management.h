#pragma once
/// Display previews through OpenColorIO: scene-linear Rec.709 pixels -> 8-bit sRGB PNG.
/// Uses $OCIO when set, else the small config shipped in share/ocio/nenrin.ocio (compiled in).
