#pragma once

// Volumes of known shape for the picking and ruler tests: a sphere's signed distance sampled on
// any grid geometry (anisotropic spacing, gantry tilt, uneven slice gaps), so the surface lies
// exactly where the analytic sphere is in patient coordinates whatever the grid.

#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/volume/volume.h"

#include <cmath>
#include <vector>

namespace lw::test {

struct KnownSphere {
    glm::dvec3 centre{0.0};
    double radius = 1.0;
};

// value = radius - |p - centre| at every voxel's patient position (float32; iso 0).
inline volume::Volume sampleSphere(glm::ivec3 dims, const volume::VolumeGeometry& geometry,
                                   const KnownSphere& sphere) {
    volume::Volume out(dims, volume::VoxelType::Float32, geometry);
    float* voxels = out.dataAs<float>();
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const glm::dvec3 p = geometry.indexToPatient({x, y, z});
                voxels[out.index(x, y, z)] = float(sphere.radius - glm::distance(p, sphere.centre));
            }
    return out;
}

// A regular, anisotropic grid (0.7 x 0.8 x 1.3 mm) around a sphere of radius 20 mm.
inline volume::Volume regularSphereVolume(KnownSphere* sphere) {
    const glm::ivec3 dims{72, 64, 40};
    const auto geometry = volume::VolumeGeometry::regular({-120.0, 40.0, 300.0}, {0.7, 0.8, 1.3});
    *sphere = {geometry.indexToPatient(glm::dvec3(dims - 1) / 2.0), 20.0};
    return sampleSphere(dims, geometry, *sphere);
}

// A CT-like stack tilted by 18.5 degrees (the rows' column direction leans, the slices advance
// along z as a tilted gantry writes them) with uneven gaps of 1.1 to 2.3 mm; sphere radius 18 mm.
inline volume::Volume tiltedSphereVolume(KnownSphere* sphere) {
    const double tilt = glm::radians(18.5);
    const glm::dvec3 axisI{1, 0, 0}, axisJ{0, std::cos(tilt), -std::sin(tilt)};
    const double gaps[] = {1.1, 2.3, 1.5, 1.8};
    std::vector<glm::dvec3> positions;
    glm::dvec3 p{-30.0, -20.0, 100.0};
    for (int k = 0; k < 38; ++k) {
        positions.push_back(p);
        p.z += gaps[k % 4];
    }
    const auto geometry =
        volume::VolumeGeometry::fromSlicePositions(axisI, axisJ, 0.9, 0.9, positions);
    const glm::ivec3 dims{64, 64, int(positions.size())};
    *sphere = {geometry.indexToPatient(glm::dvec3(dims - 1) / 2.0), 18.0};
    return sampleSphere(dims, geometry, *sphere);
}

// A camera looking at the sphere's centre from (az, el), framing it.
inline render::Camera cameraOnSphere(const KnownSphere& sphere, double az, double el,
                                     render::Projection projection, int size = 256) {
    render::CameraSetup setup;
    setup.bounds = {sphere.centre - glm::dvec3(sphere.radius),
                    sphere.centre + glm::dvec3(sphere.radius)};
    setup.azimuthDeg = az;
    setup.elevationDeg = el;
    setup.projection = projection;
    return render::Camera(setup, size, size);
}

// The iso panel's depth buffer for `camera` (what the panels keep for picking).
inline std::vector<float> depthBuffer(const render::Mesh& mesh, const render::Camera& camera) {
    std::vector<float> depth;
    render::shadeSurfaceCpu(mesh, camera, {}, &depth);
    return depth;
}

} // namespace lw::test
