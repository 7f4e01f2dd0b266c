#version 410 core
// Blinn-Phong shading of the iso-surface with the per-vertex gradient normals. The silhouette
// panel draws the same pass with colour writes off, so only its depth is kept.
in vec3 vPosition;
in vec3 vNormal;

// xyz = eye position with w = 1 (perspective), or the unit direction toward the viewer with
// w = 0 (orthographic): V = uViewer.xyz - position * uViewer.w covers both.
uniform vec4 uViewer;
uniform vec3 uLightDirection; // unit, toward the light, patient coordinates
uniform vec3 uFrontColour;
uniform vec3 uBackColour;     // inside of a surface cut open by the volume's border
uniform vec4 uMaterial;       // ambient, diffuse, specular, shininess

out vec4 fragColour;

void main() {
    vec3 v = normalize(uViewer.xyz - vPosition * uViewer.w);
    vec3 n = normalize(vNormal);
    vec3 base = uFrontColour;
    if (dot(n, v) < 0.0) {
        // Seen from inside: light it as a surface facing us so the cut is readable.
        n = -n;
        base = uBackColour;
    }
    vec3 l = uLightDirection;
    float diffuse = max(dot(n, l), 0.0);
    vec3 h = normalize(l + v);
    float specular = diffuse > 0.0 ? pow(max(dot(n, h), 0.0), uMaterial.w) : 0.0;
    vec3 colour = base * (uMaterial.x + uMaterial.y * diffuse) + vec3(uMaterial.z * specular);
    fragColour = vec4(min(colour, vec3(1.0)), 1.0);
}
