/* SPDX-License-Identifier: MPL-2.0 */
/* viewer.js -- the page `swarf simulate --html` writes: the remaining stock
 * (coloured by deviation when there is a design), the toolpath with a slider
 * through the program's lines and the tool at the chosen line, a click on
 * the part naming the line that last cut there, the alarms linked to their
 * lines, a chart of removal rate and feed per line. three.js (Debian's
 * libjs-three) is inlined before this script; the data is the JSON of
 * <script id="swarf-data"> and the mesh the base64 PLY of <script
 * id="swarf-mesh">. Once drawn, <body> gets data-ready="1",
 * data-triangles and data-lines (the tests read them).
 */
(function () {
  "use strict";
  const D = JSON.parse(document.getElementById("swarf-data").textContent);
  const $ = (id) => document.getElementById(id);

  /* The binary little-endian PLY of swarf_stock_write_mesh: float x y z
   * [uchar red green blue] [float deviation] per vertex, uchar 3 + uint i j k
   * per face. */
  function readPly(b64) {
    const bin = atob(b64), bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    const end = bin.indexOf("end_header\n") + 11, head = bin.slice(0, end).split("\n");
    let nv = 0, nf = 0, rgb = false, dev = false;
    for (const l of head) {
      const w = l.split(" ");
      if (w[0] === "element" && w[1] === "vertex") nv = +w[2];
      if (w[0] === "element" && w[1] === "face") nf = +w[2];
      if (w[0] === "property" && w[2] === "red") rgb = true;
      if (w[0] === "property" && w[2] === "deviation") dev = true;
    }
    const dv = new DataView(bytes.buffer), stride = 12 + (rgb ? 3 : 0) + (dev ? 4 : 0);
    const pos = new Float32Array(3 * nv), col = rgb ? new Float32Array(3 * nv) : null;
    let o = end;
    for (let i = 0; i < nv; i++, o += stride) {
      pos[3 * i] = dv.getFloat32(o, true);
      pos[3 * i + 1] = dv.getFloat32(o + 4, true);
      pos[3 * i + 2] = dv.getFloat32(o + 8, true);
      if (rgb) for (let k = 0; k < 3; k++) col[3 * i + k] = bytes[o + 12 + k] / 255;
    }
    const idx = new Uint32Array(3 * nf);
    for (let f = 0; f < nf; f++, o += 13) {
      if (bytes[o] !== 3) throw new Error("swarf: a face of the mesh is not a triangle");
      for (let k = 0; k < 3; k++) idx[3 * f + k] = dv.getUint32(o + 1 + 4 * k, true);
    }
    return { pos, col, idx, nf };
  }

  const view = $("view");
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f4f2);
  const camera = new THREE.PerspectiveCamera(35, 1, 0.1, 1e5);
  camera.up.set(0, 0, 1);
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x606070, 0.75));
  const sun = new THREE.DirectionalLight(0xffffff, 0.55);
  scene.add(sun);

  /* The part. */
  const ply = readPly(document.getElementById("swarf-mesh").textContent.trim());
  const geo = new THREE.BufferGeometry();
  geo.setAttribute("position", new THREE.BufferAttribute(ply.pos, 3));
  geo.setIndex(new THREE.BufferAttribute(ply.idx, 1));
  if (ply.col) geo.setAttribute("color", new THREE.BufferAttribute(ply.col, 3));
  geo.computeVertexNormals();
  geo.computeBoundingBox();
  const part = new THREE.Mesh(geo, new THREE.MeshLambertMaterial({
    color: ply.col ? 0xffffff : 0xb8bcc4, vertexColors: !!ply.col, side: THREE.DoubleSide }));
  scene.add(part);

  /* The toolpath: P = [line, kind (0 rapid, 1 feed), x, y, z, feed] a point. */
  const P = D.path, n = P.length / 6;
  const seg = new Float32Array(6 * Math.max(n - 1, 1)), segCol = new Float32Array(seg.length);
  const segLine = new Int32Array(Math.max(n - 1, 1));
  for (let i = 1; i < n; i++) {
    for (let k = 0; k < 3; k++) {
      seg[6 * (i - 1) + k] = P[6 * (i - 1) + 2 + k];
      seg[6 * (i - 1) + 3 + k] = P[6 * i + 2 + k];
    }
    const c = P[6 * i + 1] ? [0.1, 0.35, 0.85] : [0.9, 0.25, 0.2];
    for (let k = 0; k < 6; k++) segCol[6 * (i - 1) + k] = c[k % 3];
    segLine[i - 1] = P[6 * i];
  }
  const pathGeo = new THREE.BufferGeometry();
  pathGeo.setAttribute("position", new THREE.BufferAttribute(seg, 3));
  pathGeo.setAttribute("color", new THREE.BufferAttribute(segCol, 3));
  const path = new THREE.LineSegments(pathGeo, new THREE.LineBasicMaterial({ vertexColors: true }));
  scene.add(path);

  /* The tool at a line: cutter, shank and holder of its table entry. */
  const tools = {};
  for (const t of D.tools) tools[t.number] = t;
  const toolGroup = new THREE.Group();
  scene.add(toolGroup);
  function setTool(number) {
    while (toolGroup.children.length) toolGroup.remove(toolGroup.children[0]);
    const t = tools[number];
    if (!t) return;
    const add = (r0, r1, h, z, color) => {
      const g = new THREE.CylinderBufferGeometry(r1, r0, h, 32);
      g.rotateX(Math.PI / 2);
      g.translate(0, 0, z + h / 2);
      toolGroup.add(new THREE.Mesh(g, new THREE.MeshLambertMaterial({ color, transparent: true, opacity: 0.8 })));
    };
    add(t.diameter / 2, t.diameter / 2, t.length, 0, 0xd0a020);
    let z = t.length;
    if (t.stickout > t.length) add(t.shank / 2, t.shank / 2, t.stickout - t.length, z, 0x909090), (z = t.stickout);
    for (const h of t.holder || []) add(h[0] / 2, h[1] / 2, h[2], z, 0x505868), (z += h[2]);
  }

  /* Lines: the program's lines that moved, in order, and the last point of each. */
  const lines = [], lastPoint = new Map();
  for (let i = 0; i < n; i++) {
    const l = P[6 * i];
    if (!lastPoint.has(l)) lines.push(l);
    lastPoint.set(l, i);
  }
  const slider = $("slider");
  slider.max = Math.max(lines.length - 1, 0);
  slider.value = slider.max;
  const perLine = new Map();
  for (const r of D.report.lines || []) perLine.set(r.line, r);
  function showLine(k) {
    const line = lines[k], i = lastPoint.get(line);
    if (line === undefined) return;
    pathGeo.setDrawRange(0, 2 * Math.max(i, 0));
    toolGroup.position.set(P[6 * i + 2], P[6 * i + 3], P[6 * i + 4]);
    const r = perLine.get(line);
    setTool(r ? r.tool : D.tools.length ? D.tools[0].number : 0);
    $("at").textContent = "line " + line + (r ? ", T" + r.tool + ", removed " +
      (r.removed_mm3 == null ? "-" : r.removed_mm3.toFixed(2)) + " mm\u00b3" : "");
  }
  slider.oninput = () => showLine(+slider.value);
  function gotoLine(line) {
    let k = lines.findIndex((l) => l >= line);
    if (k < 0) k = lines.length - 1;
    slider.value = k;
    showLine(k);
  }

  /* A click on the part: the last feed move whose tip path passes within the
   * cutter's reach of the point (its radius and a voxel). */
  const ray = new THREE.Raycaster(), mouse = new THREE.Vector2();
  function lastCut(q) {
    const reach = (t) => (tools[t] ? tools[t].diameter / 2 : 0) + 1.5 * D.voxel;
    const a = new THREE.Vector3(), b = new THREE.Vector3(), c = new THREE.Vector3();
    for (let i = n - 1; i > 0; i--) {
      if (!P[6 * i + 1]) continue;
      a.set(P[6 * i - 4], P[6 * i - 3], P[6 * i - 2]);
      b.set(P[6 * i + 2], P[6 * i + 3], P[6 * i + 4]);
      const r = perLine.get(P[6 * i]);
      new THREE.Line3(a, b).closestPointToPoint(q, true, c);
      if (c.distanceTo(q) <= reach(r ? r.tool : 0) + 1e-9) return P[6 * i];
    }
    return 0;
  }
  renderer.domElement.addEventListener("click", (e) => {
    const box = renderer.domElement.getBoundingClientRect();
    mouse.set(((e.clientX - box.left) / box.width) * 2 - 1, -((e.clientY - box.top) / box.height) * 2 + 1);
    ray.setFromCamera(mouse, camera);
    const hit = ray.intersectObject(part)[0];
    if (!hit) return;
    const line = lastCut(hit.point);
    $("pick").textContent = line ? "last cut there: line " + line : "no move cut there (stock face)";
    if (line) gotoLine(line);
  });

  /* The alarms, each a link to its line. */
  const list = $("alarms");
  for (const a of D.report.alarms || []) {
    const li = document.createElement("li"), link = document.createElement("a");
    link.href = "#";
    link.textContent = "line " + a.line + ": " + a.kind + (a.depth ? " " + (+a.depth).toFixed(3) + " mm" : "");
    link.onclick = (e) => (e.preventDefault(), gotoLine(a.line));
    li.appendChild(link);
    list.appendChild(li);
  }
  if (!list.children.length) list.innerHTML = "<li>none</li>";

  /* The chart: removal rate (mm^3/min) and feed (mm/min) per line. */
  (function chart() {
    const cv = $("chart"), g = cv.getContext("2d"), W = cv.width, H = cv.height;
    const rows = (D.report.lines || []).filter((r) => r.time_s > 0);
    const feed = new Map();
    for (let i = 0; i < n; i++) if (P[6 * i + 1]) feed.set(P[6 * i], P[6 * i + 5]);
    const mrr = rows.map((r) => (r.removed_mm3 > 0 ? (60 * r.removed_mm3) / r.time_s : 0));
    const fr = rows.map((r) => feed.get(r.line) || 0);
    const top = (v) => Math.max(1e-9, ...v);
    g.fillStyle = "#fff";
    g.fillRect(0, 0, W, H);
    const plot = (v, color) => {
      const m = top(v);
      g.strokeStyle = color;
      g.beginPath();
      v.forEach((y, i) => g[i ? "lineTo" : "moveTo"]((i / Math.max(v.length - 1, 1)) * W, H - 4 - (y / m) * (H - 8)));
      g.stroke();
    };
    plot(fr, "#1a59d9");
    plot(mrr, "#d9401a");
    $("chartlegend").textContent = "removal rate (red, peak " + top(mrr).toFixed(0) +
      " mm\u00b3/min) and feed (blue, peak " + top(fr).toFixed(0) + " mm/min) by line";
  })();

  /* Views. */
  const bb = geo.boundingBox, centre = new THREE.Vector3(), size = new THREE.Vector3();
  bb.getCenter(centre);
  bb.getSize(size);
  const dist = 2.6 * Math.max(size.x, size.y, size.z, 1);
  const views = { iso: [-1, -1, 0.9], top: [0, -0.001, 1], front: [0, -1, 0], right: [1, 0, 0], left: [-1, 0, 0] };
  function setView(name) {
    const v = new THREE.Vector3(...views[name]).normalize().multiplyScalar(dist);
    camera.position.copy(centre).add(v);
    controls.target.copy(centre);
    controls.update();
  }
  for (const name of Object.keys(views)) {
    const bt = document.createElement("button");
    bt.textContent = name;
    bt.onclick = () => setView(name);
    $("views").appendChild(bt);
  }

  function resize() {
    const w = view.clientWidth, h = view.clientHeight;
    renderer.setSize(w, h);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
  window.addEventListener("resize", resize);
  resize();
  setView("iso");
  showLine(+slider.value);
  function frame() {
    sun.position.copy(camera.position);
    renderer.render(scene, camera);
  }
  controls.addEventListener("change", frame);
  (function loop() {
    frame();
    requestAnimationFrame(loop);
  })();
  document.body.dataset.triangles = String(ply.nf);
  document.body.dataset.lines = String(lines.length);
  selfCheck();
  document.body.dataset.ready = "1";

  /* With #check=X,Y,Z[;X,Y,Z...] in the address (the tests), the page is
   * used as a person would use it and says on <body> what it showed: a click
   * on the part where each world point appears (data-pick: the lines named,
   * 0 for none, joined by ';'; data-pickshown: the slider's line after the
   * first), a click on the first alarm's link (data-alarm: the slider's line
   * after it), the tool drawn there (data-tool: its pieces, data-toolat:
   * where, mm), the chart's inked pixels (data-chart) and the view buttons
   * whose click looks along their direction (data-views). */
  function selfCheck() {
    const m = /^#check=([-0-9.,;]+)$/.exec(location.hash);
    if (!m) return;
    const body = document.body.dataset, cv = renderer.domElement, box = cv.getBoundingClientRect();
    const picked = [];
    frame();
    for (const point of m[1].split(";")) {
      const q = new THREE.Vector3(...point.split(",").map(Number)).project(camera);
      $("pick").textContent = "";
      cv.dispatchEvent(new MouseEvent("click", { bubbles: true, clientX: box.left + ((q.x + 1) / 2) * box.width,
        clientY: box.top + ((1 - q.y) / 2) * box.height }));
      picked.push(($("pick").textContent.match(/line (\d+)/) || [0, "0"])[1]);
      if (picked.length === 1) body.pickshown = String(lines[+slider.value]);
    }
    body.pick = picked.join(";");
    const link = list.querySelector("a");
    if (link) link.click(), (body.alarm = String(lines[+slider.value]));
    body.tool = String(toolGroup.children.length);
    body.toolat = [toolGroup.position.x, toolGroup.position.y, toolGroup.position.z].map((v) => v.toFixed(3)).join(",");
    const c = $("chart"), px = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let inked = 0;
    for (let i = 0; i < px.length; i += 4) inked += px[i] + px[i + 1] + px[i + 2] < 700 ? 1 : 0;
    body.chart = String(inked);
    const seen = [], dir = new THREE.Vector3();
    for (const bt of $("views").querySelectorAll("button")) {
      bt.click();
      dir.copy(camera.position).sub(controls.target).normalize();
      if (dir.distanceTo(new THREE.Vector3(...views[bt.textContent]).normalize()) < 1e-6) seen.push(bt.textContent);
    }
    body.views = seen.join(",");
  }
})();
