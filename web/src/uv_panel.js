// The UV tab: flattens the session's rest mesh on the server (POST /api/param, `iarap param`'s energies
// and options). A disk is one chart: its layout over a checkerboard beside the 3D view and the
// checkerboard mapped onto every copy of the mesh. Any other mesh (closed, with holes, of genus or in
// pieces) comes back as an atlas: the unit square with each chart in its own colour, and on the copies
// the checkerboard through the atlas tinted by chart. The report's figures go under the button.
import { atlasCornerArrays, checkerCoordinates, drawAtlas, drawLayout, flippedAtlasFaces, flippedFaces } from './uv_layout.js';

const $ = (id) => document.getElementById(id);

// Figures of a one-chart report, one line each.
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

// What makes a mesh an atlas, in words: "closed, genus 0", "5 boundary loops", "44 pieces".
function topology(report) {
  const parts = [];
  if (report.components > 1) parts.push(`${report.components} pieces`);
  parts.push(report.boundary_loops === 0 ? 'closed' : `${report.boundary_loops} boundary loop${report.boundary_loops === 1 ? '' : 's'}`);
  if (report.genus !== null) parts.push(`genus ${report.genus}`);
  return parts.join(', ');
}

// Figures of an atlas report, one line each.
function describeAtlas(report) {
  const worst = Math.max(...report.chart_list.map((c) => c.distortion));
  return [
    `atlas of ${report.charts} charts (${topology(report)}), ${report.energy_kind} energy, ${report.parameterize_ms.toFixed(0)} ms`,
    `distortion ${report.distortion.toPrecision(3)} (energy / area; worst chart ${worst.toPrecision(3)})`,
    `${report.flipped} flipped triangles, overlap ${report.overlap_ratio === 0 ? '0' : report.overlap_ratio.toExponential(1)} of the covered texels`,
    `packing efficiency ${report.packing_efficiency.toFixed(3)} at ${report.texture_size} texels, padding ${report.padding}`,
    `seam length ${report.seam_length.toPrecision(4)}, splits ${report.splits_for_distortion} for distortion, ${report.splits_for_overlap} for overlap`,
    ...(report.degenerate_faces ? [`${report.degenerate_faces} faces without an area left out (grey)`] : []),
  ].join('\n');
}

// A number input's value, or an error naming the field when the browser finds it invalid.
function numberInput(id, name) {
  const input = $(id);
  if (!input.checkValidity() || input.value === '') throw new Error(`${name}: ${input.validationMessage || 'a number is needed'}`);
  return Number(input.value);
}

export class UvPanel {
  // api: the serve API (api.js); viewer: the Viewer; guarded: runs an action showing its error.
  constructor(api, viewer, guarded) {
    this.api = api;
    this.viewer = viewer;
    this.faces = null;
    // The last flattening of this mesh: {uv, checker, flipped, report} for one chart, {cornerUv, chart,
    // corners, flipped, report} for an atlas (report.atlas true).
    this.map = null;
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
    this.viewer.setAtlas(null);
  }

  async flatten() {
    const body = {
      energy: $('uv-energy').value,
      boundary: $('uv-boundary').value,
      allow_flips: $('uv-allow-flips').checked,
      charts: $('uv-charts').value,
      target_distortion: numberInput('uv-target-distortion', 'Target distortion'),
      max_angle: numberInput('uv-max-angle', 'Max angle'),
      texture_size: numberInput('uv-texture-size', 'Texture size'),
      padding: numberInput('uv-padding', 'Padding'),
    };
    $('uv-flatten').disabled = true;
    $('uv-info').textContent = 'flattening...';
    try {
      const { header, arrays } = await this.api.param(body);
      if (header.atlas) this.#showAtlas(header, arrays);
      else this.#showChart(header, arrays);
      $('uv-layout').hidden = false;
      this.#showTexture();
    } catch (error) {
      $('uv-info').textContent = '';
      throw error;
    } finally {
      $('uv-flatten').disabled = false;
    }
  }

  #showChart(header, arrays) {
    const checker = checkerCoordinates(arrays.uv);
    this.map = { uv: arrays.uv, checker, flipped: flippedFaces(this.faces, arrays.uv), report: header };
    $('uv-info').textContent = describe(header);
    $('uv-layout-title').textContent = 'UV layout (flipped triangles red)';
    drawLayout($('uv-layout-canvas'), this.faces, checker, this.map.flipped);
  }

  #showAtlas(header, arrays) {
    const { corner_uv: cornerUv, chart } = arrays;
    const flipped = flippedAtlasFaces(cornerUv, chart);
    this.map = { cornerUv, chart, corners: atlasCornerArrays(cornerUv, chart), flipped, report: header };
    $('uv-info').textContent = describeAtlas(header);
    $('uv-layout-title').textContent = `UV atlas: ${header.charts} charts (flipped triangles red)`;
    drawAtlas($('uv-layout-canvas'), cornerUv, chart, flipped);
  }

  #showTexture() {
    const shown = this.map && $('uv-texture').checked;
    const atlas = shown && this.map.report.atlas;
    this.viewer.setTexture(shown && !atlas ? this.map.checker : null);
    this.viewer.setAtlas(atlas ? this.map.corners : null);
  }
}
