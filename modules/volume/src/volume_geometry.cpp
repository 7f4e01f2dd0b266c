#include "lw/volume/volume_geometry.h"

#include "lw/core/error.h"

#include <algorithm>
#include <cmath>

namespace lw::volume {

VolumeGeometry VolumeGeometry::regular(glm::dvec3 origin, glm::dvec3 spacing, glm::dvec3 axisI,
                                       glm::dvec3 axisJ, glm::dvec3 axisK) {
    VolumeGeometry g;
    g.m_origin = origin;
    g.m_axisI = glm::normalize(axisI);
    g.m_axisJ = glm::normalize(axisJ);
    g.m_stackAxis = glm::normalize(axisK);
    g.m_spacingI = spacing.x;
    g.m_spacingJ = spacing.y;
    g.m_uniformStep = spacing.z;
    return g;
}

VolumeGeometry VolumeGeometry::fromSlicePositions(glm::dvec3 axisI, glm::dvec3 axisJ,
                                                  double spacingI, double spacingJ,
                                                  const std::vector<glm::dvec3>& slicePositions,
                                                  double singleSliceStep) {
    if (slicePositions.empty())
        throw core::Error("volume geometry", "a slice stack needs at least one slice position");
    VolumeGeometry g;
    g.m_origin = slicePositions.front();
    g.m_axisI = glm::normalize(axisI);
    g.m_axisJ = glm::normalize(axisJ);
    g.m_spacingI = spacingI;
    g.m_spacingJ = spacingJ;
    const glm::dvec3 normal = glm::normalize(glm::cross(g.m_axisI, g.m_axisJ));
    if (slicePositions.size() == 1) {
        g.m_stackAxis = normal;
        g.m_uniformStep = singleSliceStep;
        return g;
    }
    // The stack axis is the direction from the first to the last slice: robust against small
    // jitter in single positions, and it carries the shear of a gantry tilt.
    const glm::dvec3 span = slicePositions.back() - slicePositions.front();
    const double length = glm::length(span);
    if (length <= 0.0)
        throw core::Error("volume geometry", "all slices share one position");
    g.m_stackAxis = span / length;
    g.m_sliceOffsets.reserve(slicePositions.size());
    for (const auto& position : slicePositions)
        g.m_sliceOffsets.push_back(glm::dot(position - g.m_origin, g.m_stackAxis));
    if (g.hasUniformSlices(1e-4)) {
        g.m_uniformStep = length / double(slicePositions.size() - 1);
        g.m_sliceOffsets.clear();
    }
    return g;
}

glm::dvec3 VolumeGeometry::sliceNormal() const {
    return glm::normalize(glm::cross(m_axisI, m_axisJ));
}

double VolumeGeometry::sliceStep() const {
    if (m_sliceOffsets.size() < 2)
        return m_uniformStep;
    return (m_sliceOffsets.back() - m_sliceOffsets.front()) / double(m_sliceOffsets.size() - 1);
}

double VolumeGeometry::sliceStepAlongNormal() const {
    return sliceStep() * std::abs(glm::dot(m_stackAxis, sliceNormal()));
}

bool VolumeGeometry::hasUniformSlices(double relativeTolerance) const {
    if (m_sliceOffsets.size() < 3)
        return true;
    const double mean = sliceStep();
    for (std::size_t k = 1; k < m_sliceOffsets.size(); ++k) {
        const double gap = m_sliceOffsets[k] - m_sliceOffsets[k - 1];
        if (std::abs(gap - mean) > relativeTolerance * std::abs(mean))
            return false;
    }
    return true;
}

double VolumeGeometry::sliceOffset(double k) const {
    const std::size_t n = m_sliceOffsets.size();
    if (n < 2)
        return k * m_uniformStep;
    const double clamped = std::clamp(std::floor(k), 0.0, double(n - 2));
    const auto k0 = static_cast<std::size_t>(clamped);
    const double t = k - clamped;
    return m_sliceOffsets[k0] + t * (m_sliceOffsets[k0 + 1] - m_sliceOffsets[k0]);
}

double VolumeGeometry::sliceGap(int k) const {
    return sliceOffset(k + 1) - sliceOffset(k);
}

double VolumeGeometry::tiltDegrees() const {
    const double c = std::clamp(std::abs(glm::dot(m_stackAxis, sliceNormal())), 0.0, 1.0);
    return std::acos(c) * 180.0 / 3.14159265358979323846;
}

glm::dvec3 VolumeGeometry::indexToPatient(glm::dvec3 ijk) const {
    return m_origin + ijk.x * m_spacingI * m_axisI + ijk.y * m_spacingJ * m_axisJ +
           sliceOffset(ijk.z) * m_stackAxis;
}

double VolumeGeometry::sliceIndexAtOffset(double offset) const {
    const std::size_t n = m_sliceOffsets.size();
    if (n < 2)
        return offset / m_uniformStep;
    // The gap [k0, k0 + 1] that holds the offset, the first or last gap beyond the ends.
    const auto above =
        std::upper_bound(m_sliceOffsets.begin() + 1, m_sliceOffsets.end() - 1, offset);
    const auto k0 = std::size_t(above - m_sliceOffsets.begin()) - 1;
    const double gap = m_sliceOffsets[k0 + 1] - m_sliceOffsets[k0];
    return double(k0) + (offset - m_sliceOffsets[k0]) / gap;
}

glm::dvec3 VolumeGeometry::patientToIndex(glm::dvec3 patient) const {
    // The slice planes are parallel, so the distance along the normal gives the offset along
    // the stack axis (sheared by the tilt); what remains lies in slice 0's plane.
    const glm::dvec3 normal = sliceNormal();
    const glm::dvec3 relative = patient - m_origin;
    const double offset = glm::dot(relative, normal) / glm::dot(m_stackAxis, normal);
    const glm::dvec3 inPlane = relative - offset * m_stackAxis;
    // Solved with the axes' Gram matrix, so axes that are not quite orthogonal invert exactly.
    const double ii = glm::dot(m_axisI, m_axisI), ij = glm::dot(m_axisI, m_axisJ),
                 jj = glm::dot(m_axisJ, m_axisJ);
    const double pi = glm::dot(inPlane, m_axisI), pj = glm::dot(inPlane, m_axisJ);
    const double det = ii * jj - ij * ij;
    const double a = (jj * pi - ij * pj) / det; // mm along axisI
    const double b = (ii * pj - ij * pi) / det; // mm along axisJ
    return {a / m_spacingI, b / m_spacingJ, sliceIndexAtOffset(offset)};
}

glm::dmat3 VolumeGeometry::jacobian(double k) const {
    double step = m_uniformStep;
    if (m_sliceOffsets.size() >= 2) {
        const auto k0 =
            static_cast<int>(std::clamp(std::floor(k), 0.0, double(m_sliceOffsets.size() - 2)));
        step = m_sliceOffsets[std::size_t(k0) + 1] - m_sliceOffsets[std::size_t(k0)];
    }
    return glm::dmat3(m_spacingI * m_axisI, m_spacingJ * m_axisJ, step * m_stackAxis);
}

glm::dmat4 VolumeGeometry::affine() const {
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(m_spacingI * m_axisI, 0.0);
    m[1] = glm::dvec4(m_spacingJ * m_axisJ, 0.0);
    m[2] = glm::dvec4(sliceStep() * m_stackAxis, 0.0);
    m[3] = glm::dvec4(m_origin, 1.0);
    return m;
}

VolumeGeometry VolumeGeometry::subStack(int firstSlice, int count) const {
    VolumeGeometry g = *this;
    g.m_origin = indexToPatient({0.0, 0.0, double(firstSlice)});
    if (!m_sliceOffsets.empty()) {
        g.m_sliceOffsets.clear();
        const double base = sliceOffset(firstSlice);
        for (int k = 0; k < count; ++k)
            g.m_sliceOffsets.push_back(sliceOffset(firstSlice + k) - base);
    }
    return g;
}

VolumeGeometry VolumeGeometry::refined(glm::ivec3 factors, int slices) const {
    if (factors.x < 1 || factors.y < 1 || factors.z < 1)
        throw core::Error("volume geometry", "refinement factors must be at least 1");
    VolumeGeometry g = *this;
    g.m_spacingI = m_spacingI / factors.x;
    g.m_spacingJ = m_spacingJ / factors.y;
    g.m_uniformStep = m_uniformStep / factors.z;
    g.m_refinement = m_refinement * factors;
    if (!m_sliceOffsets.empty()) {
        g.m_sliceOffsets.clear();
        const int refinedSlices = slices > 1 ? (slices - 1) * factors.z + 1 : slices;
        for (int k = 0; k < refinedSlices; ++k)
            g.m_sliceOffsets.push_back(sliceOffset(double(k) / factors.z));
    }
    return g;
}

} // namespace lw::volume
