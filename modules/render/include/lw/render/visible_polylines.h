#pragma once

// The visible silhouette as polylines in image coordinates, for vector output (SVG, the PDF
// report) and for drawing lines of any width: whatever method drew the frame, its surface's
// Burns segments (the contour of the mesh for the camera) are chained through the mesh edges
// they cross — both triangles that share an edge put an endpoint on it, so the edge names the
// neighbour — and cut to the parts the frame's line mask shows, sampled at pixel resolution
// (methods 1 and 3 test visibility per pixel; method 2's mask is what its rays left visible).
// So the polylines are the frame's own lines, with sub-pixel positions.
//
//   mesh edge (u, v) --- segment of triangle T1 --- edge (v, w) --- segment of T2 --- ...
//   an edge shared by exactly two crossing triangles joins their segments; a border edge or a
//   fold ends a chain; a chain that comes back to its first edge is closed.

#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/pixel_mask.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace lw::render {

struct Polyline {
    std::vector<glm::vec2> points; // image coordinates: x right, y down, pixel (i, j) = [i, i+1)
    bool closed = false;           // the last point joins the first
};

struct PolylineOptions {
    // A sample can be visible only where the mask is on within this many pixels of it (the
    // accuracy score's tolerance; 0: the pixel itself), and only within this much chain length
    // of a sample on a pixel the mask has on itself (its own pixel).
    int tolerancePx = 1;
    // A run of such samples is visible when at least this share of its length lies on its own
    // pixels; else it is hidden. Keeps a hidden chain running a pixel beside a visible line, or
    // crossing it, from being drawn as visible (dense false hatching where lines crowd).
    double minOwnPixelShare = 0.5;
    // Samples per pixel of length along a segment when cutting at visibility changes.
    double samplesPerPixel = 2.0;
    // Visible runs shorter than this (pixels of length) are hidden unless nearly all on their
    // own pixels; hidden ones shorter are dropped (see minStrokePixels).
    double minLengthPx = 0.0;
    // Points within this many pixels of the line through their kept neighbours are dropped
    // (Douglas-Peucker): far below what a screen or a printer shows, and a much smaller file.
    double simplifyPx = 0.05;
};

// A line segment across one triangle of a mesh, with the mesh edges its ends lie on (the key of
// vertex indices a, b: meshEdgeKey): a Burns segment, or a suggestive contour's.
struct EdgeSegment {
    glm::vec3 point[2];
    std::uint64_t edge[2];
};
std::uint64_t meshEdgeKey(std::uint32_t a, std::uint32_t b);

// Segments chained through the edges they share (3D, patient mm, before visibility): one entry
// per chain, its points the segment endpoints in order.
struct SilhouetteChain {
    std::vector<glm::vec3> points;
    bool closed = false;
};
std::vector<SilhouetteChain> chainSegments(const std::vector<EdgeSegment>& segments);
// The Burns segments of `mesh` for `camera`, chained.
std::vector<SilhouetteChain> chainSilhouette(const Mesh& mesh, const Camera& camera);

// The parts of the chains that `lines` shows, projected to the image.
std::vector<Polyline> visiblePolylines(const std::vector<SilhouetteChain>& chains,
                                       const Camera& camera, const PixelMask& lines,
                                       const PolylineOptions& options = {});
// The same for the silhouette of `mesh` (chainSilhouette).
std::vector<Polyline> visiblePolylines(const Mesh& mesh, const Camera& camera,
                                       const PixelMask& lines, const PolylineOptions& options = {});

// The visible parts and, with `withHidden`, the hidden ones: the rest of the chains in the image,
// what `lines` does not show (PolylineOptions) -- behind the surface when the frame tested
// visibility (the technical-illustration convention draws them thin, dashed and grey:
// svg_lines.h). A hidden chain that runs beside a visible line stays hidden there. Hidden runs
// shorter than minLengthPx are dropped, so the speckle that pruning removed does not come back
// dashed. With visibility off every part is shown: none is hidden.
struct PolylineSplit {
    std::vector<Polyline> visible;
    std::vector<Polyline> hidden;
};
PolylineSplit splitPolylines(const std::vector<SilhouetteChain>& chains, const Camera& camera,
                             const PixelMask& lines, const PolylineOptions& options,
                             bool withHidden);
PolylineSplit splitPolylines(const Mesh& mesh, const Camera& camera, const PixelMask& lines,
                             const PolylineOptions& options, bool withHidden);

} // namespace lw::render
