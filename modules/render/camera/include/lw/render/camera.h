#pragma once

#include "lw/render/aabb.h"

#include <glm/glm.hpp>

namespace lw::render {

enum class Projection { Perspective, Orthographic };

// Sphere: the box's circumscribed sphere fills the viewport, so the scale does not change with
// the view direction (accuracy runs and turntables compare views). Box: the projected corners
// fill it (tighter, view dependent).
enum class FitMode { Sphere, Box };

// View direction in degrees, patient coordinates LPS (+x left, +y posterior, +z superior):
//
//              +z superior (screen up at el 0)
//               ^
//               |   +y posterior (away from the viewer at az 0)
//               |  /
//               | /
//   patient's   |/
//   right <-----+-----> +x patient's left (screen right at az 0, as radiologists expect)
//              /
//             /
//         eye at az 0, el 0: anterior (-y), looking at the face toward +y
//
// The eye direction (from the box centre toward the eye) is
//   (sin az cos el, -cos az cos el, sin el):
// az 90 = from the patient's left (+x), az 180 = from behind, az -90 = from the right,
// el 90 = from above (head-on view of the vertex; screen up is then posterior at az 0),
// el -90 = from below. Screen up is the elevation tangent (-sin az sin el, cos az sin el, cos el),
// which is +z at el 0 and never degenerates at the poles.
struct CameraSetup {
    Aabb bounds{{-1, -1, -1}, {1, 1, 1}};
    double azimuthDeg = 0.0;
    double elevationDeg = 0.0;
    Projection projection = Projection::Perspective;
    double fovYDeg = 30.0; // perspective only
    double margin = 0.05;  // free border, relative to the fitted extent
    FitMode fit = FitMode::Sphere;
    // Interactive adjustments on top of the fitted view (the GUI's trackball, pan and zoom;
    // renders from the CLI leave them at their defaults):
    double rollDeg = 0.0; // camera turned counter-clockwise about the view axis (picture clockwise)
    double zoom = 1.0;    // > 1 magnifies: the fitted extent divided by zoom
    // The look-at point moved across the screen, in units of the fitted half-height at the
    // target (x to screen right, y to screen up). Perpendicular to the view axis, so the depth of
    // the box and with it the near and far planes stay as fitted.
    glm::dvec2 pan{0.0};
};

struct Ray {
    glm::dvec3 origin{0.0};
    glm::dvec3 direction{0.0, 1.0, 0.0}; // unit length
    glm::dvec3 at(double t) const { return origin + t * direction; }
};

struct ProjectedPoint {
    // Continuous pixel coordinates: x to the right, y down, pixel (i, j) covers
    // [i, i+1) x [j, j+1) and its centre is (i + 0.5, j + 0.5).
    glm::dvec2 pixel{0.0};
    // Distance in front of the eye along the view axis (mm; the eye plane for ortho). Depth <= 0
    // means behind the eye, where a perspective pixel position is meaningless.
    double depth = 0.0;
    // Normalised device depth in [-1, 1] between the near and far planes (GL convention).
    double ndcDepth = 0.0;
};

// A camera looking at a box's centre, fitted to a width x height viewport. Matrices follow the
// OpenGL conventions (right-handed view space looking down -z, NDC depth in [-1, 1]).
class Camera {
public:
    Camera(); // the default setup on a 512 x 512 viewport
    Camera(const CameraSetup& setup, int width, int height);

    const CameraSetup& setup() const { return m_setup; }
    void setSetup(const CameraSetup& setup);
    void setView(double azimuthDeg, double elevationDeg);
    void setViewport(int width, int height);
    int width() const { return m_width; }
    int height() const { return m_height; }
    bool isOrthographic() const { return m_setup.projection == Projection::Orthographic; }

    glm::dvec3 eye() const { return m_eye; }
    glm::dvec3 target() const { return m_target; }
    glm::dvec3 forward() const { return m_forward; } // unit, from the eye into the scene
    glm::dvec3 up() const { return m_up; }           // unit, screen up
    glm::dvec3 right() const { return m_right; }     // unit, screen right
    double nearPlane() const { return m_near; }
    // Orthographic: half extents of the view (mm); perspective: tan of the half angles.
    double halfWidth() const { return m_halfWidth; }
    double halfHeight() const { return m_halfHeight; }
    double farPlane() const { return m_far; }

    // Unit vector from `point` toward the viewer: normalize(eye - point) for perspective,
    // -forward() for ortho. This is the V of Burns et al.'s d = N . V silhouette test.
    glm::dvec3 toViewer(glm::dvec3 point) const;
    // The viewer as the float shaders and kernels take it: the eye (w = 1) for perspective, the
    // unit vector toward the viewer (w = 0) for ortho; toViewer(p) = normalize(xyz - p * w).
    glm::vec4 viewerHomogeneous() const {
        return isOrthographic() ? glm::vec4(glm::vec3(-m_forward), 0.0f)
                                : glm::vec4(glm::vec3(m_eye), 1.0f);
    }

    glm::dmat4 viewMatrix() const;
    glm::dmat4 projectionMatrix() const;
    glm::dmat4 viewProjectionMatrix() const { return projectionMatrix() * viewMatrix(); }
    glm::mat4 viewProjectionMatrixF() const { return glm::mat4(viewProjectionMatrix()); }

    ProjectedPoint project(glm::dvec3 world) const;
    // The ray through continuous pixel coordinates (see ProjectedPoint::pixel). For ortho the
    // origin lies on the eye plane, which is outside the fitted box.
    Ray rayThroughPoint(glm::dvec2 pixel) const;
    // The ray through the centre of pixel (px, py), top row first.
    Ray rayThroughPixel(int px, int py) const { return rayThroughPoint({px + 0.5, py + 0.5}); }

    // The patient point at continuous pixel coordinates and normalised device depth (as a depth
    // buffer stores it, mapped from [0, 1] to [-1, 1]): the inverse of project().
    glm::dvec3 unproject(glm::dvec2 pixel, double ndcDepth) const;

    // The shaded panels' key light (GL and CPU alike): unit direction toward a light above and
    // left of the eye, so the shading shows the surface's relief (a pure headlight flattens it).
    glm::dvec3 panelLightDirection() const;

    // Size of one pixel in mm on the plane at `depth` in front of the eye (constant for ortho).
    double pixelFootprint(double depth) const;
    // Visible height in mm on the plane through the target.
    double visibleHeightAtTarget() const;

    // Side of a square image on which a voxel of `voxelSize` mm at the box centre covers about
    // `pixelsPerVoxel` pixels, for this setup (use the mean or smallest spacing as voxelSize).
    static int squareSizeForVoxelCoverage(const CameraSetup& setup, double voxelSize,
                                          double pixelsPerVoxel);

private:
    void update();

    CameraSetup m_setup;
    int m_width = 512;
    int m_height = 512;
    glm::dvec3 m_target{0.0};
    glm::dvec3 m_eye{0.0};
    glm::dvec3 m_forward{0.0, 1.0, 0.0};
    glm::dvec3 m_up{0.0, 0.0, 1.0};
    glm::dvec3 m_right{1.0, 0.0, 0.0};
    double m_distance = 1.0;  // eye to target
    double m_halfWidth = 1.0; // ortho: half extents of the view; perspective: tan of half angles
    double m_halfHeight = 1.0;
    double m_near = 0.1;
    double m_far = 10.0;
};

} // namespace lw::render
