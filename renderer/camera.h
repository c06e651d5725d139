#pragma once
/// The camera: a pinhole with a vertical field of view, or a thin lens (aperture radius and
/// focus distance). Generates primary rays with ray differentials (the rays through the
/// neighbouring pixels) for texture filtering.

#include "renderer/scene.h"

namespace nenrin {

struct Ray {
    Vec3 origin, direction;  ///< direction unit length
};

struct CameraRay {
    Ray ray;
    Ray rayX, rayY;  ///< through the pixel one step to the right / one step down
};

class Camera {
public:
    Camera(const CameraSpec& spec, int width, int height);
    /// A ray through image position (px, py) in pixels (0,0 = top-left corner of the image),
    /// lens sample (lu, lv) in [0,1)^2. `differentialScale` shortens the differentials (the
    /// footprint of one of many samples per pixel is smaller than the pixel).
    CameraRay generate(double px, double py, double lu, double lv, double differentialScale) const;
    /// The same ray without differentials.
    Ray primary(double px, double py, double lu, double lv) const {
        return through(px, py, lu, lv);
    }
    /// The unit viewing axis (for the Z AOV: depth along it).
    const Vec3& forward() const { return forward_; }
    /// A pinhole ignores the lens sample.
    bool hasLens() const { return lensRadius_ > 0; }

private:
    Ray through(double px, double py, double lu, double lv) const;

    Vec3 position_, forward_, right_, up_;
    double tanHalfY_, aspect_;
    int width_, height_;
    double lensRadius_, focusDistance_;
};

}  // namespace nenrin
