(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("replay-data").textContent);
  var times = data.t, frameCount = times.length, tStart = times[0], tEnd = times[frameCount - 1];
  var playButton = document.getElementById("play"), speedSelect = document.getElementById("speed");
  var slider = document.getElementById("time"), now = document.getElementById("now");
  var note = document.getElementById("view-note");
  var decimals = Math.max(2, Math.min(6, Math.ceil(-Math.log(data.dt) / Math.LN10) + 1));
  var current = tStart, playing = false, lastWall = null;

  // The frame at or before t, and how far t is on the way to the next one.
  function locate(list, t) {
    var lo = 0, hi = list.length - 1;
    if (!(t > list[0])) return { i: 0, j: 0, a: 0 };
    if (t >= list[hi]) return { i: hi, j: hi, a: 0 };
    while (hi - lo > 1) {
      var mid = (lo + hi) >> 1;
      if (list[mid] <= t) lo = mid; else hi = mid;
    }
    return { i: lo, j: hi, a: (t - list[lo]) / (list[hi] - list[lo]) };
  }

  // A number in a few characters; 0 when it is negligible beside `scale`.
  function short(v, scale) {
    if (v === null || !isFinite(v)) return "\u2013";
    var a = Math.abs(v);
    if (scale && a < 1e-9 * scale) return "0";
    if (a !== 0 && (a >= 1e5 || a < 1e-3)) return v.toExponential(2);
    return String(parseFloat(v.toPrecision(4)));
  }

  // --- The time series: one small plot per column, each on its own scale --------------------------------------
  function createChart() {
    var box = document.getElementById("chart");
    var names = data.series.names, values = data.series.values;
    var panels = [];
    if (names.length < 2 || values[0].length === 0) {
      box.style.display = "none";
      return { draw: function () {}, cursor: function () {} };
    }
    var ts = values[0], t0 = ts[0], t1 = ts[ts.length - 1];
    var left = 58, right = 10, top = 20, plotHeight = 58, bottom = 8;
    function escape(s) {
      return s.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");
    }
    function x(t, width) { return left + (t1 > t0 ? (t - t0) / (t1 - t0) : 0) * (width - left - right); }
    function draw() {
      var width = Math.max(220, box.clientWidth - 16), html = "", scales = [];
      for (var c = 1; c < names.length; ++c) {
        var v = values[c], lo = Infinity, hi = -Infinity;
        for (var k = 0; k < v.length; ++k) if (v[k] !== null) { lo = Math.min(lo, v[k]); hi = Math.max(hi, v[k]); }
        if (!(lo <= hi)) { lo = -1; hi = 1; }
        scales[c] = Math.max(Math.abs(lo), Math.abs(hi));
        var said = names[c] + ": from " + short(v[0], scales[c]) + " at " + short(t0) + " s to " +
          short(v[v.length - 1], scales[c]) + " at " + short(t1) + " s, between " + short(lo, scales[c]) + " and " +
          short(hi, scales[c]);
        if (hi === lo) { var pad = Math.abs(hi) * 0.1 || 1; lo -= pad; hi += pad; }
        var last = c === names.length - 1, height = top + plotHeight + bottom + (last ? 14 : 0);
        var d = "", open = false;
        for (k = 0; k < v.length; ++k) {
          if (v[k] === null) { open = false; continue; }
          var px = x(ts[k], width), py = top + (hi - v[k]) / (hi - lo) * plotHeight;
          d += (open ? "L" : "M") + px.toFixed(1) + " " + py.toFixed(1);
          open = true;
        }
        html += '<svg class="panel" role="img" aria-label="' + escape(said) + '" width="' + width + '" height="' +
          height + '" viewBox="0 0 ' + width + " " + height + '" data-column="' + c + '">' +
          '<text class="name" x="' + left + '" y="13">' + escape(names[c]) + "</text>" +
          '<text class="value" x="' + (width - right) + '" y="13" text-anchor="end"></text>' +
          '<rect class="plot" x="' + left + '" y="' + top + '" width="' + (width - left - right) + '" height="' +
          plotHeight + '"></rect>' +
          '<text x="' + (left - 4) + '" y="' + (top + 9) + '" text-anchor="end">' + short(hi, scales[c]) +
          "</text>" +
          '<text x="' + (left - 4) + '" y="' + (top + plotHeight) + '" text-anchor="end">' + short(lo, scales[c]) +
          "</text>" +
          '<path class="series" d="' + d + '"></path>' +
          '<line class="cursor" y1="' + (top - 2) + '" y2="' + (top + plotHeight + 2) + '"></line>' +
          (last ? '<text x="' + left + '" y="' + (height - 2) + '">' + short(t0) + " s</text>" +
                  '<text x="' + (width - right) + '" y="' + (height - 2) + '" text-anchor="end">' + short(t1) +
                  " s</text>" : "") +
          "</svg>";
      }
      box.innerHTML = html;
      panels = [];
      var svgs = box.querySelectorAll("svg");
      for (var s = 0; s < svgs.length; ++s) {
        panels.push({ column: s + 1, width: width, cursor: svgs[s].querySelector(".cursor"),
                      value: svgs[s].querySelector(".value"), scale: scales[s + 1] });
        svgs[s].addEventListener("click", seekFromChart);
      }
      cursor(current);
    }
    function seekFromChart(event) {
      var rect = event.currentTarget.getBoundingClientRect(), width = rect.width;
      var f = (event.clientX - rect.left - left) / (width - left - right);
      pause();
      show(t0 + Math.min(1, Math.max(0, f)) * (t1 - t0));
    }
    function cursor(t) {
      var at = locate(ts, t);
      for (var p = 0; p < panels.length; ++p) {
        var v = values[panels[p].column], a = v[at.i], b = v[at.j];
        var value = a === null || b === null ? (at.a < 0.5 ? a : b) : a + (b - a) * at.a;
        var cx = x(Math.min(t1, Math.max(t0, t)), panels[p].width).toFixed(1);
        panels[p].cursor.setAttribute("x1", cx);
        panels[p].cursor.setAttribute("x2", cx);
        panels[p].value.textContent = short(value, panels[p].scale);
      }
    }
    return { draw: draw, cursor: cursor };
  }

  // --- The time series as a table, for a reader who cannot see the chart: every k-th row, at most 200 ---------
  function createTable() {
    var box = document.getElementById("series-table");
    var names = data.series.names, values = data.series.values;
    if (names.length === 0 || values[0].length === 0) {
      box.textContent = "This run has no time series.";
      return;
    }
    var rows = values[0].length, step = Math.max(1, Math.ceil(rows / 200));
    var shown = [];
    for (var r = 0; r < rows; r += step) shown.push(r);
    if (shown[shown.length - 1] !== rows - 1) shown.push(rows - 1);
    var table = document.createElement("table");
    table.createCaption().textContent = "The time series: " + (shown.length < rows ? shown.length + " of " + rows +
      " rows, evenly spread" : rows + " rows");
    var head = table.createTHead().insertRow();
    names.forEach(function (name) {
      var th = document.createElement("th");
      th.scope = "col";
      th.textContent = name;
      head.appendChild(th);
    });
    var body = table.createTBody();
    shown.forEach(function (r) {
      var row = body.insertRow();
      for (var c = 0; c < names.length; ++c) {
        var cell = document.createElement(c === 0 ? "th" : "td");
        if (c === 0) cell.scope = "row";
        cell.textContent = values[c][r] === null ? "\u2013" : String(values[c][r]);
        row.appendChild(cell);
      }
    });
    box.appendChild(table);
  }

  // --- The bodies in 3-D ------------------------------------------------------------------------------------------
  function createScene() {
    var view = document.getElementById("view");
    var canvas = document.createElement("canvas");
    var attributes = { alpha: false, depth: true, stencil: true, antialias: true, premultipliedAlpha: true,
                       preserveDrawingBuffer: false, powerPreference: "default" };
    var gl = null;
    try { gl = canvas.getContext("webgl", attributes); } catch (e) { gl = null; }
    if (!gl) {
      note.textContent = "This browser cannot draw WebGL, so the 3-D view is off; the time series still works.";
      note.className = "alone";
      return null;
    }
    view.insertBefore(canvas, view.firstChild);
    var renderer = new THREE.WebGLRenderer({ canvas: canvas, context: gl, antialias: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    var scene = new THREE.Scene();
    scene.background = new THREE.Color(0xeef1f5);
    // Light from the sky, from above and aside, and from the camera, so that no face the camera sees is dark.
    scene.add(new THREE.HemisphereLight(0xffffff, 0x8a929c, 0.45));
    var sun = new THREE.DirectionalLight(0xffffff, 0.35);
    sun.position.set(0.5, 1, 0.75);
    scene.add(sun);
    var headlight = new THREE.DirectionalLight(0xffffff, 0.55);
    scene.add(headlight);

    var surfaceColor = new THREE.Color(0x8c9db5), lineColor = new THREE.Color(0x404850);
    var pointColor = new THREE.Color(1, 0, 1);
    var yAxis = new THREE.Vector3(0, 1, 0);

    // Where each body is in each frame; its decorations go in its group.
    var bodies = data.bodies.map(function (b) {
      var group = new THREE.Group();
      scene.add(group);
      return { group: group, p: b.p, q: b.q, shapes: 0, massless: b.massless === true };
    });
    var motion = new THREE.Box3(), point = new THREE.Vector3();
    bodies.forEach(function (b) {
      for (var f = 0; f < frameCount; ++f) motion.expandByPoint(point.fromArray(b.p, 3 * f));
    });
    var motionSize = motion.isEmpty() ? 0 : motion.getSize(new THREE.Vector3()).length();

    function withOpacity(material, s) {
      if (s.o !== undefined) { material.transparent = true; material.opacity = s.o; material.depthWrite = false; }
      return material;
    }
    function solid(geometry, s, doubleSided) {
      var color = s.c ? new THREE.Color(s.c[0], s.c[1], s.c[2]) : surfaceColor;
      if (s.w === "points") {
        return new THREE.Points(geometry, withOpacity(new THREE.PointsMaterial(
          { color: color, size: 3, sizeAttenuation: false }), s));
      }
      return new THREE.Mesh(geometry, withOpacity(new THREE.MeshPhongMaterial({
        color: color, specular: 0x222222, shininess: 30, wireframe: s.w === "wire",
        side: doubleSided ? THREE.DoubleSide : THREE.FrontSide }), s));
    }
    function segments(points, s, color) {
      var geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.Float32BufferAttribute(points, 3));
      var c = s.c ? new THREE.Color(s.c[0], s.c[1], s.c[2]) : color || lineColor;
      return new THREE.LineSegments(geometry, withOpacity(new THREE.LineBasicMaterial({ color: c }), s));
    }
    // A shape along `direction` (three.js builds cylinders and cones along y), centered at `center`.
    function along(object, direction, center) {
      var group = new THREE.Group();
      object.quaternion.setFromUnitVectors(yAxis, direction.clone().normalize());
      object.position.copy(center);
      group.add(object);
      return group;
    }
    function stick(from, to, radius, color, s) {
      var axis = new THREE.Vector3().subVectors(to, from), length = axis.length();
      var mesh = new THREE.Mesh(new THREE.CylinderBufferGeometry(radius, radius, length, 12),
        withOpacity(new THREE.MeshPhongMaterial({ color: color, specular: 0x222222, shininess: 30 }), s));
      return along(mesh, axis, from.clone().add(to).multiplyScalar(0.5));
    }
    function vector(a) { return new THREE.Vector3(a[0], a[1], a[2]); }

    function makeShape(s) {
      var group;
      switch (s.k) {
      case "sphere": return solid(new THREE.SphereBufferGeometry(s.r, 32, 20), s);
      case "ellipsoid":
        var ellipsoid = solid(new THREE.SphereBufferGeometry(1, 32, 20), s);
        ellipsoid.scale.set(s.r[0], s.r[1], s.r[2]);
        group = new THREE.Group();
        group.add(ellipsoid);
        return group;
      case "brick": return solid(new THREE.BoxBufferGeometry(2 * s.h[0], 2 * s.h[1], 2 * s.h[2]), s);
      case "cylinder": return solid(new THREE.CylinderBufferGeometry(s.r, s.r, 2 * s.h, 32), s);
      case "torus": return solid(new THREE.TorusBufferGeometry(s.r, s.t, 16, 48), s);
      case "circle":
        if (s.w === "wire") {
          var ring = [];
          for (var k = 0; k < 64; ++k) {
            var a0 = 2 * Math.PI * k / 64, a1 = 2 * Math.PI * (k + 1) / 64;
            ring.push(s.r * Math.cos(a0), s.r * Math.sin(a0), 0, s.r * Math.cos(a1), s.r * Math.sin(a1), 0);
          }
          return segments(ring, s);
        }
        return solid(new THREE.CircleBufferGeometry(s.r, 48), s, true);
      case "cone":
        var direction = vector(s.d).normalize();
        return along(solid(new THREE.ConeBufferGeometry(s.r, s.h, 32), s), direction,
                     vector(s.a).addScaledVector(direction, s.h / 2));
      case "frame":
        group = new THREE.Group();
        var axisColors = s.c ? [0, 0, 0].map(function () { return new THREE.Color(s.c[0], s.c[1], s.c[2]); })
                             : [new THREE.Color(0xd03030), new THREE.Color(0x30a030), new THREE.Color(0x3050d0)];
        for (var i = 0; i < 3; ++i) {
          var end = new THREE.Vector3();
          end.setComponent(i, s.l);
          group.add(stick(new THREE.Vector3(), end, s.l * 0.02, axisColors[i], s));
        }
        return group;
      case "line": return segments(s.a.concat(s.e), s);
      case "point":
        var p = s.a, h = 0.05;
        return segments([p[0] - h, p[1], p[2], p[0] + h, p[1], p[2], p[0], p[1] - h, p[2], p[0], p[1] + h, p[2],
                         p[0], p[1], p[2] - h, p[0], p[1], p[2] + h], s, pointColor);
      case "arrow":
        var start = vector(s.a), tipEnd = vector(s.e), shaft = new THREE.Vector3().subVectors(tipEnd, start);
        var length = shaft.length(), tip = Math.min(s.tip, length);
        group = new THREE.Group();
        if (length === 0) return group;
        var tipBase = tipEnd.clone().addScaledVector(shaft, -tip / length);
        group.add(segments([start.x, start.y, start.z, tipBase.x, tipBase.y, tipBase.z], s));
        if (tip > 0) {
          var cone = solid(new THREE.ConeBufferGeometry(tip * 0.35, tip, 16), s);
          if (!s.c) cone.material.color.copy(lineColor);
          group.add(along(cone, shaft, tipBase.clone().addScaledVector(shaft, tip / length / 2)));
        }
        return group;
      case "mesh":
        var geometry = new THREE.BufferGeometry();
        geometry.setAttribute("position", new THREE.Float32BufferAttribute(s.v, 3));
        geometry.setIndex(s.f);
        geometry.computeVertexNormals();
        return solid(geometry, s, true);
      }
      return null;
    }

    var ground = new THREE.Group();
    scene.add(ground);
    data.shapes.forEach(function (s) {
      var object = makeShape(s);
      if (!object) return;
      if (s.T) {
        object.position.set(s.T[0], s.T[1], s.T[2]);
        object.quaternion.set(s.T[3], s.T[4], s.T[5], s.T[6]);
      }
      if (s.s) object.scale.set(s.s[0], s.s[1], s.s[2]);
      if (s.b === 0) {
        ground.add(object);
      } else {
        bodies[s.b - 1].group.add(object);
        bodies[s.b - 1].shapes++;
      }
    });
    // A body that has no decoration is a small sphere, so that nothing moves unseen; a massless one (a slider that
    // only carries a joint) is no matter, and is not drawn.
    var defaultRadius = motionSize > 0 ? 0.03 * motionSize : 0.05;
    bodies.forEach(function (b) {
      if (b.shapes === 0 && !b.massless) b.group.add(solid(new THREE.SphereBufferGeometry(defaultRadius, 24, 16), {}));
    });

    // The camera sees the whole motion: every body's reach around its origin, at every frame.
    var extent = new THREE.Box3(), corner = new THREE.Vector3();
    // How far a body's decorations reach from its origin: its farthest vertex, its group still at the origin.
    function reachOf(group) {
      var reach = 0;
      group.updateMatrixWorld(true);
      group.traverse(function (object) {
        var position = object.geometry && object.geometry.getAttribute("position");
        if (!position) return;
        for (var k = 0; k < position.count; ++k) {
          reach = Math.max(reach, corner.fromBufferAttribute(position, k).applyMatrix4(object.matrixWorld).length());
        }
      });
      return reach;
    }
    bodies.forEach(function (b) {
      var reach = reachOf(b.group);
      var pad = new THREE.Vector3(reach, reach, reach);
      for (var f = 0; f < frameCount; ++f) {
        point.fromArray(b.p, 3 * f);
        extent.expandByPoint(point.clone().sub(pad));
        extent.expandByPoint(point.clone().add(pad));
      }
      // A body that goes far beyond its own size leaves a trail.
      if (motionSize > 0 && frameCount > 1) {
        var own = new THREE.Box3();
        for (f = 0; f < frameCount; ++f) own.expandByPoint(point.fromArray(b.p, 3 * f));
        if (own.getSize(new THREE.Vector3()).length() > 3 * reach) {
          var geometry = new THREE.BufferGeometry();
          geometry.setAttribute("position", new THREE.Float32BufferAttribute(b.p, 3));
          b.trail = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0xa85f28 }));
          scene.add(b.trail);
          // ... and a dot of a fixed size on screen where it is: a body small beside its motion (an apple in a
          // 78 m fall) stays in sight at any distance.
          var dot = new THREE.BufferGeometry();
          dot.setAttribute("position", new THREE.Float32BufferAttribute([0, 0, 0], 3));
          b.group.add(new THREE.Points(dot, new THREE.PointsMaterial({ color: 0xb0202c, size: 10, sizeAttenuation: false })));
        }
      }
    });
    if (extent.isEmpty()) extent.setFromObject(ground);
    if (extent.isEmpty()) extent.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    var center = extent.getCenter(new THREE.Vector3()), size = extent.getSize(new THREE.Vector3()).length();
    if (!(size > 0)) size = 1;

    // A grid on the ground (y = 0) when the motion is near it.
    if (extent.min.y - 0.5 * size <= 0 && extent.max.y + 0.5 * size >= 0) {
      var cell = Math.pow(10, Math.floor(Math.log(size / 8) / Math.LN10)), steps = [1, 2, 5, 10];
      for (var k = 0; k < steps.length && size / 8 > steps[k] * cell * 1.5; ++k);
      cell *= steps[Math.min(k, 3)];
      var cells = 2 * Math.ceil((Math.max(extent.max.x - extent.min.x, extent.max.z - extent.min.z) + size) / cell / 2);
      var grid = new THREE.GridHelper(cells * cell, cells, 0xb4bcc6, 0xd2d8de);
      grid.position.set(Math.round(center.x / cell) * cell, 0, Math.round(center.z / cell) * cell);
      scene.add(grid);
    }

    var camera = new THREE.PerspectiveCamera(25, 1, size / 1000, size * 100);
    var viewFrom = new THREE.Vector3(0.35, 0.3, 1).normalize();  // looking at the x-y plane, from above and aside
    var startFrom = viewFrom.clone(), zoom = 1;
    var controls = null, moved = false;
    if (THREE.OrbitControls) {
      controls = new THREE.OrbitControls(camera, renderer.domElement);
      controls.enableKeys = false;
      controls.addEventListener("change", function () { moved = true; dirty = true; });
      note.textContent = "Drag to turn, scroll to zoom, right-drag to move.";
    }
    note.textContent += (note.textContent ? " " : "") +
      "From the keyboard, with the view selected (Tab): the arrow keys turn it, + and - zoom, 0 sets it back; " +
      "or the buttons at the right.";
    if (data.skipped > 0) {
      note.textContent += (note.textContent ? " " : "") + data.skipped +
        (data.skipped === 1 ? " decoration (text) is" : " decorations (text) are") + " not shown.";
    }

    // Places the camera on viewFrom so that every corner of the extent is in view.
    function frameAll() {
      var aspect = camera.aspect, tanV = Math.tan(camera.fov * Math.PI / 360), tanH = tanV * aspect;
      var xc = new THREE.Vector3().crossVectors(yAxis, viewFrom).normalize();
      var yc = new THREE.Vector3().crossVectors(viewFrom, xc);
      var distance = 0;
      for (var k = 0; k < 8; ++k) {
        corner.set(k & 1 ? extent.max.x : extent.min.x, k & 2 ? extent.max.y : extent.min.y,
                   k & 4 ? extent.max.z : extent.min.z).sub(center);
        var depth = corner.dot(viewFrom);
        distance = Math.max(distance, depth + 1.08 * Math.abs(corner.dot(xc)) / tanH,
                            depth + 1.08 * Math.abs(corner.dot(yc)) / tanV);
      }
      camera.position.copy(center).addScaledVector(viewFrom, zoom * Math.max(distance, size / 100));
      camera.up.set(0, 1, 0);
      camera.lookAt(center);
      if (controls) { controls.target.copy(center); controls.update(); moved = false; }
    }

    var dirty = true, qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
    function resize() {
      var width = Math.max(1, view.clientWidth), height = Math.max(1, view.clientHeight);
      renderer.setSize(width, height, false);
      camera.aspect = width / height;
      camera.updateProjectionMatrix();
      if (!moved) frameAll();
      dirty = true;
    }
    // The keyboard's way to turn and zoom the view: 15 degrees a key about the vertical or across it (short of the
    // poles), a fifth nearer or farther.
    function turnBy(key) {
      var step = Math.PI / 12;
      if (key === "ArrowLeft" || key === "ArrowRight") {
        viewFrom.applyAxisAngle(yAxis, key === "ArrowLeft" ? -step : step);
      } else if (key === "ArrowUp" || key === "ArrowDown") {
        var across = new THREE.Vector3().crossVectors(yAxis, viewFrom).normalize();
        var turned = viewFrom.clone().applyAxisAngle(across, key === "ArrowUp" ? -step : step);
        if (Math.abs(turned.y) < 0.97) viewFrom.copy(turned);
      } else if (key === "+" || key === "=") {
        zoom /= 1.25;
      } else if (key === "-" || key === "_") {
        zoom *= 1.25;
      } else if (key === "0" || key === "Home") {
        viewFrom.copy(startFrom);
        zoom = 1;
      } else {
        return false;
      }
      moved = false;
      frameAll();
      dirty = true;
      return true;
    }
    view.addEventListener("keydown", function (event) {
      if (event.altKey || event.ctrlKey || event.metaKey || event.target.tagName === "BUTTON") return;
      if (turnBy(event.key)) event.preventDefault();
    });
    // The same with a tap or a click, for a pointer that cannot drag.
    var buttons = document.getElementById("view-turn");
    buttons.hidden = false;
    buttons.addEventListener("click", function (event) {
      var key = event.target.getAttribute("data-key");
      if (key) turnBy(key);
    });

    function pose(t) {
      var at = locate(times, t);
      bodies.forEach(function (b) {
        b.group.position.set(b.p[3 * at.i] + (b.p[3 * at.j] - b.p[3 * at.i]) * at.a,
                             b.p[3 * at.i + 1] + (b.p[3 * at.j + 1] - b.p[3 * at.i + 1]) * at.a,
                             b.p[3 * at.i + 2] + (b.p[3 * at.j + 2] - b.p[3 * at.i + 2]) * at.a);
        qa.fromArray(b.q, 4 * at.i);
        qb.fromArray(b.q, 4 * at.j);
        THREE.Quaternion.slerp(qa, qb, b.group.quaternion, at.a);
        if (b.trail) b.trail.geometry.setDrawRange(0, at.i + 1);
      });
      dirty = true;
    }
    function render() {
      if (!dirty) return;
      headlight.position.subVectors(camera.position, controls ? controls.target : center);
      renderer.render(scene, camera);
      dirty = false;
    }
    resize();
    return { pose: pose, render: render, resize: resize };
  }

  var chart = createChart();
  chart.draw();
  createTable();
  var view3d = createScene();

  function show(t) {
    current = Math.min(tEnd, Math.max(tStart, t));
    slider.value = current;
    now.textContent = "t = " + current.toFixed(decimals) + " s";
    slider.setAttribute("aria-valuetext", now.textContent);
    if (view3d) view3d.pose(current);
    chart.cursor(current);
  }
  function play() {
    if (current >= tEnd) show(tStart);
    playing = true;
    lastWall = null;
    playButton.textContent = "Pause";
  }
  function pause() {
    playing = false;
    playButton.textContent = "Play";
  }
  function tick(wall) {
    if (playing) {
      if (lastWall !== null) {
        var t = current + (wall - lastWall) / 1000 * Number(speedSelect.value);
        if (t >= tEnd) { t = tEnd; pause(); }
        show(t);
      }
      lastWall = wall;
    }
    if (view3d) view3d.render();
    window.requestAnimationFrame(tick);
  }
  // "#t=1.5": paused at t = 1.5 s.
  function timeInLink() {
    var match = /(?:^#|&)t=([^&]*)/.exec(window.location.hash);
    var t = match ? parseFloat(decodeURIComponent(match[1])) : NaN;
    return isFinite(t) ? t : null;
  }

  slider.min = tStart;
  slider.max = tEnd;
  playButton.addEventListener("click", function () { if (playing) pause(); else play(); });
  slider.addEventListener("input", function () { show(Number(slider.value)); lastWall = null; });
  window.addEventListener("resize", function () { chart.draw(); if (view3d) view3d.resize(); });
  window.addEventListener("hashchange", function () {
    var t = timeInLink();
    if (t !== null) { pause(); show(t); }
  });
  document.addEventListener("keydown", function (event) {
    var tag = event.target.tagName;
    if (event.key !== " " || tag === "BUTTON" || tag === "SELECT" || tag === "INPUT") return;
    event.preventDefault();
    if (playing) pause(); else play();
  });

  // It plays from the start, unless the reader asks for less motion (then Play, or the space bar, starts it).
  var start = timeInLink();
  var still = window.matchMedia && window.matchMedia("(prefers-reduced-motion: reduce)").matches;
  show(start === null ? tStart : start);
  if (start === null && !still) play();
  window.requestAnimationFrame(tick);
})();
