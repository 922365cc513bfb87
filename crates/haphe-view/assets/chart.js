// The force and penetration chart over the last seconds: force (N) on the left axis,
// penetration (mm) on the right, both starting at zero.

export class Chart {
  constructor(canvas, seconds) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.seconds = seconds;
    this.points = []; // [t, force N, penetration mm]
  }

  push(t, force, penetrationMm) {
    const last = this.points[this.points.length - 1];
    if (last && t < last[0]) this.points.length = 0; // a new run or a jump back
    this.points.push([t, force, penetrationMm]);
    const from = t - this.seconds;
    let drop = 0;
    while (drop < this.points.length && this.points[drop][0] < from) drop++;
    if (drop > 0) this.points.splice(0, drop);
  }

  replace(points) {
    this.points = points;
  }

  draw() {
    const { ctx, canvas, points } = this;
    const w = canvas.width, h = canvas.height;
    const left = 44, right = 48, top = 18, bottom = 22;
    ctx.clearRect(0, 0, w, h);
    ctx.font = '11px system-ui, sans-serif';
    ctx.fillStyle = '#9aa3ad';
    ctx.fillText(`force (N) and penetration (mm), last ${this.seconds} s`, left, 12);
    const tEnd = points.length ? points[points.length - 1][0] : 0;
    const tStart = tEnd - this.seconds;
    let fMax = 0.5, pMax = 0.5;
    for (const p of points) { fMax = Math.max(fMax, p[1]); pMax = Math.max(pMax, p[2]); }
    fMax = niceCeil(fMax); pMax = niceCeil(pMax);
    const x = (t) => left + ((t - tStart) / this.seconds) * (w - left - right);
    const yF = (f) => h - bottom - (f / fMax) * (h - top - bottom);
    const yP = (p) => h - bottom - (p / pMax) * (h - top - bottom);
    ctx.strokeStyle = '#444c56';
    ctx.strokeRect(left, top, w - left - right, h - top - bottom);
    ctx.fillStyle = '#ffb347';
    ctx.fillText(fMax.toString(), 6, top + 8);
    ctx.fillText('0', 6, h - bottom);
    ctx.fillStyle = '#6cb6ff';
    ctx.fillText(pMax.toString(), w - right + 4, top + 8);
    ctx.fillText('0', w - right + 4, h - bottom);
    ctx.fillStyle = '#9aa3ad';
    ctx.fillText(`t = ${tEnd.toFixed(2)} s`, w - right - 70, h - 6);
    const line = (color, y, k) => {
      ctx.strokeStyle = color;
      ctx.lineWidth = 1.5;
      ctx.beginPath();
      points.forEach((p, i) => (i ? ctx.lineTo(x(p[0]), y(p[k])) : ctx.moveTo(x(p[0]), y(p[k]))));
      ctx.stroke();
    };
    line('#6cb6ff', yP, 2);
    line('#ffb347', yF, 1);
  }
}

function niceCeil(v) {
  const e = Math.pow(10, Math.floor(Math.log10(v)));
  for (const m of [1, 2, 5, 10]) if (m * e >= v) return +(m * e).toPrecision(3);
  return v;
}
