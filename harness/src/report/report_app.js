// report_app.js — the interactive part of report.html and of `vobench plot --out FILE.html`, embedded
// into the page at build time with plotly.js (report/interactive_page.cpp). It reads the page's data
// island (<script type="application/json" id="vobench-data">, built by report/trajectory_view.cpp)
// and draws, for the chosen view: a 3-D trajectory viewer (ground truth and the aligned estimate,
// coloured by the ATE residual, orbit and zoom), a time slider that moves each track's camera frustum
// and names the frame's ATE and RPE, the RPE over time of every entry on the same sequence and sensor
// (hover, zoom), and the cell's per-frame timing by stage. It also filters the report's tables by
// sensor, sequence and algorithm. Every text from a config or a plugin reaches the page through
// textContent (never innerHTML) and reaches plotly through plotText(), which escapes its markup.
(function () {
  'use strict';
  var island = document.getElementById('vobench-data');
  if (!island || typeof Plotly === 'undefined') return;
  var data = JSON.parse(island.textContent);
  // The colour-blind-safe palette of the gnuplot figures (report/gnuplot.cpp colour()), same order.
  var palette = ['#0072B2', '#E69F00', '#009E73', '#D55E00', '#56B4E9', '#CC79A7', '#F0E442'];
  var font = {family: 'system-ui, sans-serif', size: 12};

  function plotText(s) {
    return String(s).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
  }
  function el(tag, className, text) {
    var e = document.createElement(tag);
    if (className) e.className = className;
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function fixed(x, d) { return x === null || x === undefined ? '–' : Number(x).toFixed(d); }

  // Rotates v by the unit quaternion q = [w, x, y, z]: v + 2w (u × v) + 2 u × (u × v), u = (x, y, z).
  function rotate(q, v) {
    var w = q[0], x = q[1], y = q[2], z = q[3];
    var cx = y * v[2] - z * v[1], cy = z * v[0] - x * v[2], cz = x * v[1] - y * v[0];
    return [v[0] + 2 * (w * cx + y * cz - z * cy), v[1] + 2 * (w * cy + z * cx - x * cz), v[2] + 2 * (w * cz + x * cy - y * cx)];
  }
  function at(flat, i, n) { return flat.slice(i * n, i * n + n); }
  // The last index whose stamp is at or before t (0 when none is).
  function indexAt(stamps, t) {
    var lo = 0, hi = stamps.length - 1;
    if (hi < 0 || stamps[0] > t) return 0;
    while (lo < hi) {
      var mid = (lo + hi + 1) >> 1;
      if (stamps[mid] <= t) lo = mid; else hi = mid - 1;
    }
    return lo;
  }

  // A camera frustum at pose i of a track (camera-to-world, TUM convention: camera z forward, x right,
  // y down), as one line trace with null gaps: apex to the four corners, then the image rectangle.
  function frustum(track, i, depth) {
    var q = at(track.q, i, 4), p = at(track.p, i, 3);
    var w = 0.5 * depth, h = 0.375 * depth;
    var corners = [[-w, -h, depth], [w, -h, depth], [w, h, depth], [-w, h, depth]].map(function (c) {
      var r = rotate(q, c);
      return [r[0] + p[0], r[1] + p[1], r[2] + p[2]];
    });
    var x = [], y = [], z = [];
    function put(a) { x.push(a ? a[0] : null); y.push(a ? a[1] : null); z.push(a ? a[2] : null); }
    corners.forEach(function (c) { put(p); put(c); put(null); });
    [0, 1, 2, 3, 0].forEach(function (k) { put(corners[k]); });
    return {x: x, y: y, z: z};
  }

  function extent(tracks) {
    var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    tracks.forEach(function (tr) {
      for (var i = 0; i + 2 < tr.p.length; i += 3)
        for (var a = 0; a < 3; ++a) {
          if (tr.p[i + a] === null) continue;
          lo[a] = Math.min(lo[a], tr.p[i + a]);
          hi[a] = Math.max(hi[a], tr.p[i + a]);
        }
    });
    return Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 0.1);
  }

  // One view: the 3-D scene, the slider and the frame's figures, the RPE and timing charts.
  function Explorer(root, views, peersOf) {
    this.root = root;
    this.views = views;
    this.peersOf = peersOf;
    root.textContent = '';
    this.title = root.appendChild(el('h3', 'view-title'));
    this.note = root.appendChild(el('p', 'view-note'));
    this.scene = root.appendChild(el('div', 'viewer3d'));
    this.scene.id = 'viewer3d';
    var bar = root.appendChild(el('div', 'slider-bar'));
    bar.appendChild(el('label', '', 'time '));
    this.slider = bar.appendChild(el('input'));
    this.slider.type = 'range';
    this.slider.id = 'frame-slider';
    this.info = bar.appendChild(el('span', 'frame-info'));
    this.info.id = 'frame-info';
    this.rpe = root.appendChild(el('div', 'chart'));
    this.rpe.id = 'rpe-chart';
    this.timingNote = root.appendChild(el('p', 'timing-note'));
    this.timing = root.appendChild(el('div', 'chart'));
    this.timing.id = 'timing-chart';
    var self = this, pending = false;
    this.slider.addEventListener('input', function () {
      if (pending) return;
      pending = true;
      window.requestAnimationFrame(function () { pending = false; self.moveTo(Number(self.slider.value)); });
    });
  }

  Explorer.prototype.show = function (k) {
    var v = this.views[k], self = this;
    this.view = v;
    this.title.textContent = v.title || [v.entry, v.row, v.sensor].filter(function (s) { return s && s !== '–'; }).join(' — ');
    var notes = [];
    if (v.shown < v.poses) notes.push('Trajectories shown decimated: ' + v.shown + ' of ' + v.poses + ' poses (every k-th; the metrics use all).');
    if (v.rpe && v.rpe.shown < v.rpe.pairs) notes.push('RPE: ' + v.rpe.shown + ' of ' + v.rpe.pairs + ' pairs shown.');
    if (v.cell) notes.push('Cell ' + v.cell + '.');
    this.note.textContent = notes.join(' ');
    // The timeline: the track with the most poses.
    this.timeline = v.tracks.reduce(function (a, b) { return b.t.length > a.t.length ? b : a; }, v.tracks[0]);
    this.depth = 0.06 * extent(v.tracks);
    var traces = [], frusta = [];
    v.tracks.forEach(function (tr, i) {
      var n = tr.t.length, x = [], y = [], z = [], text = [];
      for (var j = 0; j < n; ++j) {
        x.push(tr.p[3 * j]); y.push(tr.p[3 * j + 1]); z.push(tr.p[3 * j + 2]);
        text.push('t = ' + fixed(tr.t[j], 3) + ' s' + (tr.err ? '<br>ATE ' + fixed(tr.err[j], 4) + ' m' : ''));
      }
      var colour = tr.role === 'reference' ? '#444444' : palette[i % palette.length];
      var line = {width: tr.role === 'reference' ? 3 : 5, color: colour};
      if (tr.err) {
        line = {width: 6, color: tr.err, colorscale: 'Viridis', showscale: true, cmin: 0,
                colorbar: {title: {text: 'ATE [m]'}, thickness: 14, len: 0.7}};
      }
      traces.push({type: 'scatter3d', mode: 'lines', name: plotText(tr.label), x: x, y: y, z: z, line: line,
                   text: text, hovertemplate: '%{text}<extra></extra>'});
    });
    v.tracks.forEach(function (tr, i) {
      var f = frustum(tr, 0, self.depth);
      frusta.push(traces.length);
      traces.push({type: 'scatter3d', mode: 'lines', name: plotText(tr.label) + ' (camera)', x: f.x, y: f.y, z: f.z,
                   showlegend: false, hoverinfo: 'skip',
                   line: {width: 4, color: tr.role === 'reference' ? '#444444' : (tr.err ? '#D55E00' : palette[i % palette.length])}});
    });
    this.frusta = frusta;
    var axis = function (name) { return {title: {text: name + ' [m]'}}; };
    var layout = {margin: {l: 0, r: 0, t: 10, b: 0}, font: font, showlegend: true, legend: {x: 0, y: 1},
                  scene: {aspectmode: 'data', xaxis: axis('x'), yaxis: axis('y'), zaxis: axis('z')}};
    this.slider.min = 0;
    this.slider.max = Math.max(0, this.timeline.t.length - 1);
    this.slider.value = 0;
    var drawn = Plotly.react(this.scene, traces, layout, {responsive: true, displaylogo: false});
    this.drawRpe(v);
    this.drawTiming(v);
    this.moveTo(0);
    return drawn;
  };

  Explorer.prototype.moveTo = function (i) {
    var v = this.view, self = this, t = this.timeline.t[i];
    var x = [], y = [], z = [], info = [];
    v.tracks.forEach(function (tr) {
      var f = frustum(tr, indexAt(tr.t, t), self.depth);
      x.push(f.x); y.push(f.y); z.push(f.z);
    });
    Plotly.restyle(this.scene, {x: x, y: y, z: z}, this.frusta);
    info.push('t = ' + fixed(t, 3) + ' s (pose ' + (i + 1) + ' of ' + this.timeline.t.length + ' shown)');
    v.tracks.forEach(function (tr) {
      if (tr.err) info.push('ATE ' + fixed(tr.err[indexAt(tr.t, t)], 4) + ' m');
    });
    if (v.rpe && v.rpe.t.length) {
      var k = indexAt(v.rpe.t, t);
      info.push('RPE of the pair from ' + fixed(v.rpe.t[k], 3) + ' s: ' + fixed(v.rpe.trans[k], 4) + ' m / ' + fixed(v.rpe.rot[k], 3) + '°');
    }
    this.info.textContent = info.join(' · ');
    var line = function (yref) { return {type: 'line', xref: 'x', yref: yref, x0: t, x1: t, y0: 0, y1: 1, line: {color: '#D55E00', width: 1}}; };
    if (this.rpe.data) Plotly.relayout(this.rpe, {shapes: [line('paper')]});
    if (this.timing.data) Plotly.relayout(this.timing, {shapes: [line('paper')]});
  };

  // Translational and rotational RPE over time: this view bold, the other entries on the same
  // sequence and sensor beside it.
  Explorer.prototype.drawRpe = function (v) {
    if (!v.rpe) { Plotly.purge(this.rpe); this.rpe.textContent = 'No RPE for this view.'; return; }
    var peers = this.peersOf ? this.peersOf(v) : [v], traces = [];
    peers.forEach(function (p, i) {
      if (!p.rpe) return;
      var self = p === v, colour = palette[i % palette.length];
      var style = {width: self ? 2.5 : 1, color: colour};
      var name = plotText(p.entry || p.title || 'estimate');
      traces.push({type: 'scatter', mode: 'lines', name: name, legendgroup: name, x: p.rpe.t, y: p.rpe.trans, line: style,
                   opacity: self ? 1 : 0.6, hovertemplate: '%{x:.3f} s: %{y:.4f} m<extra>' + name + '</extra>'});
      traces.push({type: 'scatter', mode: 'lines', name: name, legendgroup: name, showlegend: false, x: p.rpe.t, y: p.rpe.rot,
                   xaxis: 'x', yaxis: 'y2', line: style, opacity: self ? 1 : 0.6,
                   hovertemplate: '%{x:.3f} s: %{y:.3f}°<extra>' + name + '</extra>'});
    });
    Plotly.react(this.rpe, traces, {
      font: font, height: 420, margin: {l: 60, r: 10, t: 30, b: 40}, hovermode: 'closest',
      title: {text: 'RPE over time (pairs by their first pose)', font: {size: 13}},
      grid: {rows: 2, columns: 1, shared_xaxes: true},
      xaxis: {title: {text: 'time [s]'}, anchor: 'y2'}, yaxis: {title: {text: 'translation [m]'}, domain: [0.55, 1], rangemode: 'tozero'},
      yaxis2: {title: {text: 'rotation [°]'}, domain: [0, 0.45], rangemode: 'tozero'},
      legend: {orientation: 'h', y: -0.15}
    }, {responsive: true, displaylogo: false});
  };

  // Per-frame process time stacked by stage (bucket means when the run was long), reading beside it.
  Explorer.prototype.drawTiming = function (v) {
    var tm = v.timing;
    if (!tm) {
      Plotly.purge(this.timing);
      this.timing.textContent = '';
      this.timingNote.textContent = v.timing_error ? 'Timing: ' + v.timing_error : '';
      return;
    }
    var traces = [], shares = [];
    var total = tm.process.reduce(function (s, x) { return s + (x || 0); }, 0);
    tm.stages.forEach(function (s, i) {
      var sum = s.ms.reduce(function (a, x) { return a + (x || 0); }, 0);
      shares.push(s.name + ' ' + (total > 0 ? (100 * sum / total).toFixed(1) : '–') + ' %');
      traces.push({type: 'scatter', mode: 'lines', stackgroup: 'stages', name: plotText(s.name), x: tm.t, y: s.ms,
                   line: {width: 0.5, color: palette[i % palette.length]},
                   hovertemplate: '%{x:.3f} s: %{y:.3f} ms<extra>' + plotText(s.name) + '</extra>'});
    });
    traces.push({type: 'scatter', mode: 'lines', name: 'process() in all', x: tm.t, y: tm.process, line: {color: '#000000', width: 1.5},
                 hovertemplate: '%{x:.3f} s: %{y:.3f} ms<extra>process()</extra>'});
    traces.push({type: 'scatter', mode: 'lines', name: 'reading the frame', x: tm.t, y: tm.read, line: {color: '#999999', width: 1, dash: 'dot'},
                 hovertemplate: '%{x:.3f} s: %{y:.3f} ms<extra>reading</extra>'});
    this.timingNote.textContent = 'Timing of this cell: ' + tm.rows + ' frames' + (tm.bucket > 1 ? ', shown as means of ' + tm.bucket + ' frames' : '') +
        (tm.lost ? ', ' + tm.lost + ' lost' : '') + (tm.dropped ? ', ' + tm.dropped + ' dropped' : '') +
        (shares.length ? '. Share of process() time by stage: ' + shares.join(', ') + '.' : '. The plugin reports no stages.');
    Plotly.react(this.timing, traces, {
      font: font, height: 320, margin: {l: 60, r: 10, t: 30, b: 40}, hovermode: 'closest',
      title: {text: 'Time per frame', font: {size: 13}},
      xaxis: {title: {text: 'time [s]'}}, yaxis: {title: {text: 'ms per frame'}, rangemode: 'tozero'},
      legend: {orientation: 'h', y: -0.25}
    }, {responsive: true, displaylogo: false});
  };

  // The report's tables filtered by sensor, sequence and algorithm: rows carry data-entry, data-row
  // and data-sensor (escaped attributes); a table without a column for one of them ignores it.
  function setUpFilters(bar) {
    var rows = Array.prototype.slice.call(document.querySelectorAll('table.filterable tbody tr'));
    var keys = [['entry', 'algorithm'], ['row', 'sequence'], ['sensor', 'sensor']], selects = {};
    keys.forEach(function (k) {
      var values = {};
      rows.forEach(function (r) { if (r.dataset[k[0]] !== undefined) values[r.dataset[k[0]]] = true; });
      var names = Object.keys(values).sort();
      var label = bar.appendChild(el('label', '', k[1] + ' '));
      var s = label.appendChild(el('select'));
      s.id = 'filter-' + k[0];
      s.appendChild(el('option', '', 'all')).value = '';
      names.forEach(function (n) { s.appendChild(el('option', '', n)).value = n; });
      selects[k[0]] = s;
      s.addEventListener('change', function () { apply(); remember(); });
    });
    // The filters live in the address too (report.html#entry=put_vo&sensor=Kinect%20v2), so that a
    // filtered view can be linked to; a value the page does not have is ignored.
    var wanted = {};
    location.hash.replace(/^#/, '').split('&').forEach(function (kv) {
      var at = kv.indexOf('=');
      if (at > 0) {
        try { wanted[decodeURIComponent(kv.slice(0, at))] = decodeURIComponent(kv.slice(at + 1)); } catch (e) { /* not ours */ }
      }
    });
    keys.forEach(function (k) {
      var s = selects[k[0]], w = wanted[k[0]];
      if (w !== undefined && Array.prototype.some.call(s.options, function (o) { return o.value === w; })) s.value = w;
    });
    function remember() {
      var parts = keys.filter(function (k) { return selects[k[0]].value !== ''; }).map(function (k) {
        return k[0] + '=' + encodeURIComponent(selects[k[0]].value);
      });
      history.replaceState(null, '', parts.length ? '#' + parts.join('&') : location.pathname);
    }
    function apply() {
      rows.forEach(function (r) {
        r.hidden = keys.some(function (k) {
          var want = selects[k[0]].value, have = r.dataset[k[0]];
          return want !== '' && have !== undefined && have !== want;
        });
      });
      document.querySelectorAll('table.filterable').forEach(function (t) {
        t.dataset.visible = Array.prototype.filter.call(t.tBodies[0].rows, function (r) { return !r.hidden; }).length;
      });
    }
    apply();
  }

  var root = document.getElementById('explorer');
  if (!root) return;
  var views = data.views || [];
  var filterBar = document.getElementById('filters');
  if (filterBar) setUpFilters(filterBar);
  if (!views.length) { root.textContent = 'No trajectory to show.'; document.body.dataset.viewer = 'none'; return; }
  var peersOf = function (v) {
    return views.filter(function (p) { return p.row === v.row && p.sensor === v.sensor; });
  };
  var explorer = new Explorer(root, views, data.kind === 'report' ? peersOf : null);
  document.querySelectorAll('tr[data-view]').forEach(function (tr) {
    tr.classList.add('pickable');
    tr.addEventListener('click', function () {
      document.querySelectorAll('tr.picked').forEach(function (p) { p.classList.remove('picked'); });
      tr.classList.add('picked');
      explorer.show(Number(tr.dataset.view));
      root.scrollIntoView({behavior: 'smooth'});
    });
  });
  var first = Math.min(Math.max(Number(data.initial_view) || 0, 0), views.length - 1);
  Promise.resolve(explorer.show(first)).then(function () {
    document.body.dataset.viewer = 'drawn';
    // Everything the page fetched (there must be nothing but inline data: the tests read this).
    var fetched = performance.getEntriesByType('resource').filter(function (e) { return !/^(data|blob):/.test(e.name); });
    document.body.dataset.resources = String(fetched.length);
    document.body.dataset.views = String(views.length);
    var box = explorer.scene.getBoundingClientRect();
    document.body.dataset.viewerRect = [box.left + window.scrollX, box.top + window.scrollY, box.width, box.height].map(Math.round).join(',');
  });
})();
