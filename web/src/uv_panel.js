// The UV tab: flattens the session's rest mesh on the server (POST /api/param, `iarap param`'s energies
// and options), shows the layout over a checkerboard beside the 3D view and the checkerboard mapped onto
// every copy of the mesh, with the report's figures (energy, flipped triangles, min det J, distortion).
import { checkerCoordinates, drawLayout, flippedFaces } from './uv_layout.js';

const $ = (id) => document.getElementById(id);

// Figures of a report, one line each.
function describe(report) {
  const area = report.area_distortion;
  const angle = report.angle_distortion;
  return [
    `${report.energy_kind} energy, ${report.iterations} iterations${report.converged ? ' (converged)' : ''}, ${report.parameterize_ms.toFixed(0)} ms`,
    `energy ${report.energy.toPrecision(5)} (at best scale ${report.scaled_energy.toPrecision(5)})`,
    `${report.flipped} flipped triangles, min det J ${report.min_det_J.toPrecision(3)}`,
    `area sigma1*sigma2 median ${area.median.toPrecision(3)} [${area.min.toPrecision(3)}, ${area.max.toPrecision(3)}]`,
    `angle sigma1/sigma2 median ${angle.median.toPrecision(3)}, max ${angle.max === null ? 'inf' : angle.max.toPrecision(3)}`,
    ...(report.init_fallback ? [`the ${report.requested_init} start flipped ${report.init_flipped} triangles: started from tutte`] : []),
  ].join('\n');
}

export class UvPanel {
  // api: the serve API (api.js); viewer: the Viewer; guarded: runs an action showing its error.
  constructor(api, viewer, guarded) {
    this.api = api;
    this.viewer = viewer;
    this.faces = null;
    this.map = null; // {uv, checker, flipped, report} of the last flattening of this mesh
    $('uv-flatten').addEventListener('click', () => guarded(() => this.flatten()));
    $('uv-texture').addEventListener('change', () => this.#showTexture());
    $('uv-layout-close').addEventListener('click', () => { $('uv-layout').hidden = true; });
  }

  // A new mesh: the previous map and its pictures go.
  setMesh(faces) {
    this.faces = faces;
    this.map = null;
    $('uv-info').textContent = '';
    $('uv-layout').hidden = true;
    this.viewer.setTexture(null);
  }

  async flatten() {
    $('uv-flatten').disabled = true;
    $('uv-info').textContent = 'flattening...';
    try {
      const { header, arrays } = await this.api.param({
        energy: $('uv-energy').value,
        boundary: $('uv-boundary').value,
        allow_flips: $('uv-allow-flips').checked,
      });
      const checker = checkerCoordinates(arrays.uv);
      this.map = { uv: arrays.uv, checker, flipped: flippedFaces(this.faces, arrays.uv), report: header };
      $('uv-info').textContent = describe(header);
      drawLayout($('uv-layout-canvas'), this.faces, checker, this.map.flipped);
      $('uv-layout').hidden = false;
      this.#showTexture();
    } catch (error) {
      $('uv-info').textContent = '';
      throw error;
    } finally {
      $('uv-flatten').disabled = false;
    }
  }

  #showTexture() {
    this.viewer.setTexture(this.map && $('uv-texture').checked ? this.map.checker : null);
  }
}
