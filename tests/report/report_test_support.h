#pragma once

// What the report tests share: a QGuiApplication on the offscreen platform (fonts, QPainter
// text), the review of a sphere of known radius rendered like the CLI's export, and annotations
// on it.

#include "lw/annotation/annotation.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/report/export_image.h"
#include "lw/report/qt_image.h"
#include "picking_volumes.h"

#include <QGuiApplication>
#include <memory>

namespace lw::test {

inline void ensureGuiApplication() {
    if (QGuiApplication::instance())
        return;
    static int argc = 3;
    static char name[] = "report_tests", platform[] = "-platform", offscreen[] = "offscreen";
    static char* argv[] = {name, platform, offscreen, nullptr};
    static QGuiApplication application(argc, argv);
}

struct SphereReview {
    KnownSphere sphere;
    volume::Volume volume;
    render::Mesh mesh;
};

inline const SphereReview& sphereReview() {
    static const SphereReview review = [] {
        SphereReview r;
        r.volume = regularSphereVolume(&r.sphere);
        r.mesh = render::extractIsoSurface(r.volume, 0.0);
        return r;
    }();
    return review;
}

// Both panels at size x size, re-rendered (not scaled) like an export: the shaded surface and
// method 3's silhouette on the CPU.
inline report::RenderedPanels renderSphereReview(int size) {
    const SphereReview& review = sphereReview();
    report::RenderedPanels panels;
    panels.camera = cameraOnSphere(review.sphere, 30, 20, render::Projection::Perspective, size);
    panels.iso = report::toQImage(render::shadeSurfaceCpu(review.mesh, panels.camera));
    auto renderer =
        render::createSilhouetteRenderer(render::SilhouetteMethod::ZBuffer, render::Backend::Cpu);
    renderer->setVolume(review.volume);
    render::SilhouetteSettings settings;
    settings.isoReal = 0.0;
    panels.silhouette = report::toQImage(renderer->render(panels.camera, settings)
                                             .lines.toImage({0, 0, 0, 255}, {255, 255, 255, 255}));
    return panels;
}

// A ruler across the sphere, a label above it and an angle at its centre.
inline std::vector<annotation::Annotation> sphereAnnotations() {
    const KnownSphere& s = sphereReview().sphere;
    const glm::dvec3 c = s.centre, x{s.radius, 0, 0}, z{0, 0, s.radius};
    return {
        {annotation::AnnotationKind::Ruler, {c - x, c + x}, {}},
        {annotation::AnnotationKind::Label, {c + 0.5 * z}, "Finding A"},
        {annotation::AnnotationKind::Angle, {c + x, c, c + z}, {}},
    };
}

// A ruler across the sphere on the axial slice through its centre (slices 2 mm apart), as the
// slice tools place it: "40.0 mm · axial Z mm" with Z the centre's z.
inline annotation::Annotation sphereSliceRuler() {
    const KnownSphere& s = sphereReview().sphere;
    const glm::dvec3 c = s.centre, x{s.radius, 0, 0};
    annotation::Annotation ruler{annotation::AnnotationKind::Ruler, {c - x, c + x}, {}};
    ruler.slice = annotation::SlicePlacement{annotation::SliceOrientation::Axial, c.z, 2.0};
    return ruler;
}

} // namespace lw::test
