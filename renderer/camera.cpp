#include "renderer/camera.h"

#include <cmath>
#include <numbers>

namespace nenrin {

Camera::Camera(const CameraSpec& spec, int width, int height)
    : position_(spec.position),
      forward_(normalize(spec.lookAt - spec.position)),
      tanHalfY_(std::tan(0.5 * spec.verticalFov)),
      aspect_(double(width) / height),
      width_(width),
      height_(height),
      lensRadius_(spec.apertureRadius),
      focusDistance_(spec.focusDistance > 0 ? spec.focusDistance
                                            : length(spec.lookAt - spec.position)) {
    right_ = normalize(cross(forward_, spec.up));
    up_ = cross(right_, forward_);
}

Ray Camera::through(double px, double py, double lu, double lv) const {
    double x = (2 * px / width_ - 1) * tanHalfY_ * aspect_;
    double y = (1 - 2 * py / height_) * tanHalfY_;
    Vec3 dir = normalize(forward_ + right_ * x + up_ * y);
    if (lensRadius_ <= 0) return {position_, dir};
    // Thin lens: the point at the focus distance along the pinhole ray stays sharp.
    double r = lensRadius_ * std::sqrt(lu), phi = 2 * std::numbers::pi * lv;
    Vec3 lensPoint = position_ + right_ * (r * std::cos(phi)) + up_ * (r * std::sin(phi));
    Vec3 focus = position_ + dir * (focusDistance_ / dot(dir, forward_));
    return {lensPoint, normalize(focus - lensPoint)};
}

CameraRay Camera::generate(double px, double py, double lu, double lv,
                           double differentialScale) const {
    CameraRay c;
    c.ray = through(px, py, lu, lv);
    c.rayX = through(px + differentialScale, py, lu, lv);
    c.rayY = through(px, py + differentialScale, lu, lv);
    return c;
}

}  // namespace nenrin
