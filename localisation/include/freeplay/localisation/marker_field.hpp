#pragma once
// The fiducial marker field the sandtray game shows on `sandtray/signals/robot_localising`: 15 square markers
// (ids 700–714) in 3 rows of 5, 80 mm wide at a 100 mm pitch, the first 60 mm right of and 25 mm below the
// screen's top-left corner (the `sandtray` origin), ids row by row from there; and the 5 s it stays on screen.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <opencv2/core.hpp>

namespace freeplay::localisation {

/// Layout of a grid of square markers on the screen, in the `sandtray` frame (x right, y up, z out of the screen).
struct MarkerField {
  int first_id = 700;         ///< id of the top-left marker; ids grow along each row, then row by row
  int columns = 5;            ///< markers per row
  int rows = 3;               ///< rows
  double size_m = 0.080;      ///< side of one marker, its black border included (m)
  double pitch_m = 0.100;     ///< distance between the top-left corners of neighbouring markers (m)
  double origin_x_m = 0.060;  ///< top-left corner of the first marker, right of the screen origin (m)
  double origin_y_m = 0.025;  ///< top-left corner of the first marker, below the screen origin (m)

  /// Number of markers.
  int count() const { return columns * rows; }
  /// The id of marker `index` (0 = top-left).
  int id(int index) const { return first_id + index; }
  /// The index of marker `id`, or nothing when the field has no such marker.
  std::optional<int> index_of(int id) const;
  /// Corners of marker `index` in `sandtray` (z = 0), in the order the detector reports them: top-left,
  /// top-right, bottom-right, bottom-left as seen on the screen.
  std::array<Eigen::Vector3d, 4> corners(int index) const;
};

/// The field of the real system (`sandtray_localisation`'s configuration).
MarkerField real_marker_field();

/// Physical area the game's marker picture covers (`res/tags/markers.svg` scaled to 0.60 × 0.33 m at the origin).
inline constexpr double kFieldPictureWidthM = 0.60;
/// Height of that area (m).
inline constexpr double kFieldPictureHeightM = 0.33;
/// Opacity of the picture's white background over the game.
inline constexpr double kFieldBackgroundOpacity = 0.8;

/// Draws the marker picture over a screen image (BGR or grey, rows top first, spanning the whole
/// 0.600 × 0.335 m screen): the white background at 0.8 opacity, then every marker with exact pixel coverage.
void draw_marker_field(cv::Mat& screen, const MarkerField& field = real_marker_field());

/// When the game shows the marker field: for 5 s after each `robot_localising` signal (a new signal restarts it).
class MarkerDisplay {
 public:
  /// How long the markers stay on screen (s).
  static constexpr double kDurationS = 5.0;
  /// The signal arrived at sandtray time `t`.
  void on_signal(double t) { shown_at_ = t; }
  /// True while the markers are on screen at time `t`.
  bool showing(double t) const { return shown_at_ && t >= *shown_at_ && t < *shown_at_ + kDurationS; }

 private:
  std::optional<double> shown_at_;
};

}  // namespace freeplay::localisation
