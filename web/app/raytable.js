// The ray tree of one pixel as a table: one row per ray of `rtk debug --json`, depth first
// (shadow rays under the hit that sent them, then reflection and refraction), with each
// hit's point, t, object, material, per-light terms and the colour the ray returns.
// Numbers print as `rtk debug` prints them: 9 significant digits (printf's %.9g).
import { flattenRays, shadowStyle, RAY_STYLE } from './view3d.js';

export function g9(x) {
  if (x === null || x === undefined) return 'null';
  if (x === 0) return Object.is(x, -0) ? '-0' : '0';
  const exp = Number(x.toExponential(8).split('e')[1]);
  const strip = (s) => (s.includes('.') ? s.replace(/0+$/, '').replace(/\.$/, '') : s);
  if (exp < -4 || exp >= 9) {
    const [m, e] = x.toExponential(8).split('e');
    const n = Math.abs(Number(e));
    return `${strip(m)}e${e[0] === '-' ? '-' : '+'}${n < 10 ? '0' : ''}${n}`;
  }
  return strip(x.toFixed(8 - exp));
}

export const vec = (v) => (v ? `(${v.map(g9).join(', ')})` : '');

const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);

function swatch(c) {
  const b = c.map((x) => Math.round(255 * Math.min(1, Math.max(0, x ?? 0))));
  return `<span class="swatch" style="background: rgb(${b.join(',')})"></span>`;
}

function hitCell(hit, ray) {
  if (!hit && ray.light_hit) return `<b>light L${ray.light_hit.light}</b><br><span class="muted">its square, emission ${vec(ray.light_hit.emission)}</span>`;
  if (!hit) return '<span class="muted">no hit</span>';
  let what = hit.primitive + (hit.part ? ` ${hit.part}` : '') + (hit.triangle !== null ? ` #${hit.triangle}` : '');
  return `<b>${esc(hit.node)}</b><br><span class="muted">${esc(what)}</span>`;
}

function lightsCell(ray) {
  return ray.lights.map((l) =>
    `<div class="light-term"><b>L${l.light}</b> ${l.kind}: N·L ${g9(l.n_dot_l)}, N·H ${g9(l.n_dot_h)}<br>` +
    `ambient ${vec(l.ambient)} diffuse ${vec(l.diffuse)} specular ${vec(l.specular)}<br>` +
    `distance atten. ${g9(l.distance_attenuation)}${l.light_cosine !== undefined && l.light_cosine !== 1 ? `, cosine at the light ${g9(l.light_cosine)}` : ''}, shadow ${vec(l.shadow_attenuation)} → ${swatch(l.contribution)}${vec(l.contribution)}</div>`).join('');
}

function materialCell(hit) {
  if (!hit) return '';
  if (!hit.kd) return `${esc(hit.material)}<br><span class="muted">transmittance ${vec(hit.transmittance)}</span>`;
  return `${esc(hit.material)}<br><span class="muted">k_d ${vec(hit.kd)} k_s ${vec(hit.ks)} k_t ${vec(hit.kt)} n ${g9(hit.shininess)} ior ${g9(hit.index_of_refraction)}${hit.total_internal_reflection ? ' · total internal reflection' : ''}</span>`;
}

// Fills tbody with the rows of doc; onHover(i) with the row's index (-1 on leave).
export function fillRayTable(tbody, doc, onHover) {
  const rows = flattenRays(doc);
  tbody.innerHTML = rows.map(({ ray, level, sample }, i) => {
    const style = ray.kind === 'shadow' ? shadowStyle(ray) : RAY_STYLE[ray.kind] ? ray.kind : 'other';
    const label = ray.kind === 'shadow' ? `shadow → L${ray.light}` : ray.half_vector ? `${ray.kind} (H ${vec(ray.half_vector)})` : ray.kind;
    return `<tr data-index="${i}" data-kind="${esc(ray.kind)}" data-sample="${sample}">` +
      `<td class="kind" style="padding-left:${0.5 + level * 1.1}em"><span class="ray-dot" style="background:${RAY_STYLE[style].color}"></span>${esc(label)}</td>` +
      `<td class="depth">${ray.depth}</td>` +
      `<td class="node">${hitCell(ray.hit, ray)}</td>` +
      `<td class="t">${ray.hit ? g9(ray.hit.t) : ''}</td>` +
      `<td class="point">${ray.hit ? vec(ray.hit.point) : `<span class="muted">dir ${vec(ray.direction)}</span>`}</td>` +
      `<td class="material">${materialCell(ray.hit)}</td>` +
      `<td class="lights">${lightsCell(ray)}</td>` +
      `<td class="color">${swatch(ray.color)}<span class="color-text">${vec(ray.color)}</span></td></tr>`;
  }).join('');
  for (const tr of tbody.children) {
    tr.addEventListener('mouseenter', () => onHover?.(Number(tr.dataset.index)));
    tr.addEventListener('mouseleave', () => onHover?.(-1));
  }
  return rows.length;
}
