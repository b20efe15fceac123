#pragma once
// Two renders of the same ray map put into one image (the render dock's
// comparison modes), pixel for pixel: nothing is scaled or blended, so each
// part of a composition equals the single render it comes from. Captions go
// into a strip above the pixels, never over them.

#include <QImage>
#include <QString>

namespace paintlab::gui {

enum class CompareMode { Single, SideBySide, Split };

// Gap between the two images of a side-by-side composition, in pixels.
constexpr int kSideBySideGap = 4;

// Columns [0, column) from `left`, [column, width) from `right`; both must
// have the same size (else a null image). column is clamped to [0, width].
QImage splitImage(const QImage& left, const QImage& right, int column);
// `left`, a dark gap of kSideBySideGap columns, `right` (top-aligned; a null
// side leaves its place dark).
QImage sideBySideImage(const QImage& left, const QImage& right);
// The split column for a divider at `fraction` (0..1) of the width.
int splitColumn(int width, double fraction);

// `pixels` under a caption strip: `left_label` at the left, `right_label` at
// the right; a tick marks `divider_column` (split view; < 0: none). Saving
// the image saves this (what the dock shows, captions included).
QImage captionedImage(const QImage& pixels, const QString& left_label, const QString& right_label,
                      int divider_column);

}  // namespace paintlab::gui
