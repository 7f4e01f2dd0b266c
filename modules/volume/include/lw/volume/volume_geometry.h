#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace lw::volume {

// Maps voxel indices to patient coordinates (DICOM LPS, millimetres) without resampling.
//
//   p(i, j, k) = origin + i * spacingI * axisI + j * spacingJ * axisJ + offset(k) * stackAxis
//
// axisI/axisJ are the in-plane row and column directions (DICOM ImageOrientationPatient).
// stackAxis is the unit direction in which successive slices advance; it equals the slice
// normal axisI x axisJ unless the gantry was tilted, in which case the volume is sheared and
// the angle between the two is the tilt. offset(k) is the distance of slice k from slice 0
// along stackAxis: either k * sliceStep (uniform) or read from the per-slice list, so
// unevenly spaced series are placed exactly where the scanner put each slice. Fractional k
// interpolates linearly between neighbouring slices (and extrapolates with the end gaps).
class VolumeGeometry {
public:
    // Identity axes, unit spacing, origin 0.
    VolumeGeometry() = default;

    // A regular grid: unit axes, per-axis spacing, stackAxis == axisK.
    static VolumeGeometry regular(glm::dvec3 origin, glm::dvec3 spacing,
                                  glm::dvec3 axisI = {1, 0, 0}, glm::dvec3 axisJ = {0, 1, 0},
                                  glm::dvec3 axisK = {0, 0, 1});

    // A slice stack: in-plane axes and spacing plus the patient position of each slice's first
    // voxel, already sorted along the stack. Positions need not be evenly spaced nor lie on the
    // slice normal (gantry tilt). Needs at least one position; with one, the step along the
    // normal is `singleSliceStep`.
    static VolumeGeometry fromSlicePositions(glm::dvec3 axisI, glm::dvec3 axisJ, double spacingI,
                                             double spacingJ,
                                             const std::vector<glm::dvec3>& slicePositions,
                                             double singleSliceStep = 1.0);

    glm::dvec3 origin() const { return m_origin; }
    glm::dvec3 axisI() const { return m_axisI; }
    glm::dvec3 axisJ() const { return m_axisJ; }
    glm::dvec3 stackAxis() const { return m_stackAxis; }
    glm::dvec3 sliceNormal() const;
    double spacingI() const { return m_spacingI; }
    double spacingJ() const { return m_spacingJ; }
    // Mean distance between neighbouring slices along stackAxis.
    double sliceStep() const;
    // (spacingI, spacingJ, mean slice step).
    glm::dvec3 spacing() const { return {m_spacingI, m_spacingJ, sliceStep()}; }
    // Distance between slices along the slice normal (what radiologists call slice spacing).
    double sliceStepAlongNormal() const;

    // True when all gaps equal the mean within `relativeTolerance`.
    bool hasUniformSlices(double relativeTolerance = 1e-3) const;
    // Per-slice offsets along stackAxis; empty for a uniform grid.
    const std::vector<double>& sliceOffsets() const { return m_sliceOffsets; }
    double sliceOffset(double k) const;
    // Gap between slice k and k+1 along stackAxis.
    double sliceGap(int k) const;

    // Tilt: angle between stackAxis and the slice normal, in degrees (0 for an orthogonal grid).
    double tiltDegrees() const;
    bool isTilted(double toleranceDegrees = 0.01) const { return tiltDegrees() > toleranceDegrees; }

    glm::dvec3 indexToPatient(glm::dvec3 ijk) const;
    // The inverse: fractional (i, j, k) of a patient point, outside [0, dims - 1] where the point
    // lies outside the voxel centres (slices extrapolated with the end gaps, as sliceOffset).
    glm::dvec3 patientToIndex(glm::dvec3 patient) const;
    // The inverse of sliceOffset: the fractional slice index at `offset` along stackAxis.
    double sliceIndexAtOffset(double offset) const;
    // Columns: dp/di, dp/dj, dp/dk on the slab between slices floor(k) and floor(k)+1.
    glm::dmat3 jacobian(double k) const;
    // Index -> patient as one affine matrix, with the mean slice step (exact when uniform).
    glm::dmat4 affine() const;

    // Describes the same grid restricted to slices [firstSlice, firstSlice + count).
    VolumeGeometry subStack(int firstSlice, int count) const;
    // The same box sampled `factors` times as densely along (i, j, k): spacing divided by the
    // factor, and on an uneven stack each gap split into equal parts (sliceOffset(k / factor)),
    // so index n * factor of the refined grid is index n of this one. `slices` is this stack's
    // slice count (the per-slice list of a uniform grid is empty).
    VolumeGeometry refined(glm::ivec3 factors, int slices) const;
    // Samples per sample of the grid this one was refined from ((1, 1, 1) unless refined()): the
    // field is that grid's, so what depends on how thick its slabs are (method 2's neighbour
    // reach, the terraces of a thick-slice series) still can.
    glm::ivec3 refinement() const { return m_refinement; }

private:
    glm::dvec3 m_origin{0.0};
    glm::dvec3 m_axisI{1, 0, 0};
    glm::dvec3 m_axisJ{0, 1, 0};
    glm::dvec3 m_stackAxis{0, 0, 1};
    double m_spacingI = 1.0;
    double m_spacingJ = 1.0;
    double m_uniformStep = 1.0;         // used when m_sliceOffsets is empty
    std::vector<double> m_sliceOffsets; // offsets along stackAxis, m_sliceOffsets[0] == 0
    glm::ivec3 m_refinement{1};
};

} // namespace lw::volume
