#pragma once
/// Split jobs: a frame (or a baked grid) is cut into N bands of whole rows, one per task of a
/// cluster job, and put back together by `nenrin merge`. Band edges fall on the renderer's or
/// baker's tile rows, so a band's samples are exactly those of the one-machine job and the
/// merged result is byte-identical to it.

namespace nenrin {

/// Rows [begin, end) of an image; end < 0 means to the bottom.
struct RowBand {
    int begin = 0, end = -1;
};

/// Part `part` (1-based) of `parts` of `rows` rows, cut on multiples of `alignment` rows:
/// the tile rows are shared out as evenly as they go. Throws InputError (located at `option`)
/// unless 1 <= part <= parts <= the number of tile rows.
RowBand bandOfPart(int rows, int alignment, int part, int parts, const char* option = "--tile");

}  // namespace nenrin
