  // ---------- robust K_max over a box of the loop's parameters ----------
  // Inlined into the page's script (see serve/mod.rs). The box's parameters are the library's
  // (`sweep --param`'s names, from /api/limits); the answer is `hapstab kmax --robust --box …
  // --json`'s, drawn as the K range stable for every plant checked at its damping B, with the
  // command line's text beside it.
  const BOX = {
    params: [["arm-stiffness", "N/m"], ["arm-mass", "kg"], ["arm-damping", "Ns/m"], ["delay-time", "s"], ["period", "s"]].map((p) => ({ name: p[0], unit: p[1] })),
    seq: 0, answer: null, text: null, timer: null,
  };
  function boxUnit(name) { const p = BOX.params.find((q) => q.name === name); return p ? p.unit : ""; }
  function boxDefault() {
    return $("plant_kind").value === "tf" ? "delay-time:0:0.001" : "arm-stiffness:0:2000";
  }
  // One side of the box: the parameter, its lowest and highest value in its unit, and a remover.
  function boxRow(name, lo, hi) {
    const row = document.createElement("div");
    row.className = "row box-row";
    const sel = document.createElement("select");
    // a name the list does not hold (a link's, before /api/limits answers) is kept: the server
    // names it if it is wrong
    const known = BOX.params.some((p) => p.name === name);
    for (const p of known || !name ? BOX.params : BOX.params.concat([{ name: name, unit: "?" }])) {
      const o = document.createElement("option");
      o.value = p.name;
      o.textContent = p.name + " [" + p.unit + "]";
      sel.appendChild(o);
    }
    sel.value = name || BOX.params[0].name;
    sel.className = "box-param";
    const span = document.createElement("span");
    span.className = "box-range";
    for (const [cls, v, title] of [["box-lo", lo, "lowest value"], ["box-hi", hi, "highest value"]]) {
      const i = document.createElement("input");
      i.type = "number"; i.step = "any"; i.className = cls; i.value = v; i.title = title;
      i.addEventListener("input", onBoxChange);
      span.appendChild(i);
    }
    const rm = document.createElement("button");
    rm.type = "button"; rm.textContent = "×"; rm.title = "remove this parameter"; rm.className = "box-remove";
    rm.addEventListener("click", () => { row.remove(); if (!$("box-rows").children.length) setBoxString(boxDefault()); onBoxChange(); });
    sel.addEventListener("change", onBoxChange);
    row.append(sel, span, rm);
    return row;
  }
  // The box as the API and the command line take it: NAME:LO:HI,NAME:LO:HI.
  function boxString() {
    return Array.from($("box-rows").children).map((r) =>
      r.querySelector(".box-param").value + ":" + r.querySelector(".box-lo").value.trim() + ":" + r.querySelector(".box-hi").value.trim()).join(",");
  }
  function setBoxString(s) {
    const rows = s.split(",").map((t) => t.trim().split(":")).filter((p) => p.length === 3);
    $("box-rows").replaceChildren(...rows.map((p) => boxRow(p[0], p[1], p[2])));
  }
  function robustKmaxOn() { return $("show-robust-kmax").checked && mode() === "physical"; }
  // The robust K_max's part of a query (the API's names), or of the page's URL (box_damping:
  // the URL's wall_damping is the selected wall's).
  function robustKmaxQuery(q, forUrl) {
    q.set("box", boxString());
    q.set(forUrl ? "box_damping" : "wall_damping", $("box_damping").value.trim() || "0");
    return q;
  }
  // Typing waits a quarter second before asking the server.
  function onBoxChange() {
    clearTimeout(BOX.timer);
    if (robustKmaxOn()) BOX.timer = setTimeout(fetchRobustKmax, 250);
    writeUrl(); updateExports();
  }
  async function fetchRobustKmax() {
    const seq = ++BOX.seq;
    $("robust-kmax-note").textContent = "computing the robust K_max…";
    $("robust-kmax-note").classList.remove("box-error");
    try {
      const data = await getJson("/api/region?" + robustKmaxQuery(plantQuery()).toString());
      if (seq !== BOX.seq) return;
      BOX.answer = data.robust_kmax;
      BOX.text = data.robust_kmax_text;
      $("robust-kmax-note").textContent = "";
      $("plot").dataset.robustKmax = BOX.answer.k_max == null ? "" : String(BOX.answer.k_max);
    } catch (e) {
      if (seq !== BOX.seq) return;
      BOX.answer = null;
      BOX.text = null;
      $("robust-kmax-note").textContent = "robust K_max: " + e.message;
      $("robust-kmax-note").classList.add("box-error");
      $("plot").dataset.robustKmax = "";
    }
    drawRobustKmax();
  }
  // After the region is drawn: a new loop needs a new robust K_max.
  function robustKmaxAfterRegion() {
    if (robustKmaxOn()) fetchRobustKmax(); else { BOX.answer = null; drawRobustKmax(); }
  }
  // The segment K_min < K < K_max at B with a diamond at K_max, its label, and the summary line.
  function drawRobustKmax() {
    const r = BOX.answer, ph = state.region && state.region.physical;
    const show = !!(r && ph && state.view && robustKmaxOn() && r.k_max != null);
    $("robust-kmax-mark").setAttribute("visibility", show ? "visible" : "hidden");
    $("rk-label").setAttribute("visibility", show ? "visible" : "hidden");
    $("sum-robust-kmax").classList.toggle("hidden", !(r && robustKmaxOn()));
    $("rk-card").classList.toggle("hidden", !(r && robustKmaxOn()));
    if (!robustKmaxOn()) {
      $("robust-kmax-note").textContent = $("show-robust-kmax").checked ? "The robust K_max over a box works in physical units." : "";
      return;
    }
    if (!r) return;
    showRobustKmaxText(BOX.text || []);
    const bt = eng(r.wall_damping, "Ns/m", 4);
    $("sum-robust-kmax").textContent = r.k_max == null ? "Robust: no K is stable at B = " + bt + " for every plant of the box."
      : "Robust K_max = " + eng(r.k_max, "N/m", 6) + " at B = " + bt + " for the box (" + r.plants_verified + " random plants verified).";
    if (!show) return;
    const y = py(r.wall_damping / ph.b_per_unit), x0 = px(r.k_min / ph.k_per_unit), x1 = px(r.k_max / ph.k_per_unit);
    const set = (id, a) => { for (const k in a) $(id).setAttribute(k, a[k]); };
    set("rk-line", { x1: x0, y1: y, x2: x1, y2: y });
    $("rk-dot").setAttribute("d", "M" + x1 + "," + (y - 7) + "L" + (x1 + 7) + "," + y + "L" + x1 + "," + (y + 7) + "L" + (x1 - 7) + "," + y + "Z");
    // the label beside the marker, on the side where it fits inside the plot, else centred
    const lab = $("rk-label");
    lab.textContent = "robust K_max = " + eng(r.k_max, "N/m", 6);
    const w = lab.getComputedTextLength ? lab.getComputedTextLength() : 180, right = PLOT.x + PLOT.w - 4;
    const [x, anchor] = x1 + 10 + w <= right ? [x1 + 10, "start"] : x1 - 10 - w >= PLOT.x + 4 ? [x1 - 10, "end"]
      : [Math.max(PLOT.x + 4 + w / 2, Math.min(right - w / 2, x1)), "middle"];
    set("rk-label", { x: x, y: Math.min(PLOT.y + PLOT.h - 6, y + 20), "text-anchor": anchor });
  }
  // The command line's text under the region: its label column (box, robust, nominal,
  // checked; blank for a continued item) beside each line's text.
  function showRobustKmaxText(lines) {
    $("rk-text").replaceChildren(...lines.flatMap((l) => {
      const label = document.createElement("span"), text = document.createElement("span");
      label.textContent = l.slice(0, 10).trim();
      text.textContent = l.slice(10);
      return [label, text];
    }));
  }
  function bindRobustKmax() {
    $("box-add").addEventListener("click", () => {
      const used = boxString().split(",").map((t) => t.split(":")[0]);
      const next = BOX.params.find((p) => !used.includes(p.name)) || BOX.params[0];
      $("box-rows").appendChild(boxRow(next.name, "", ""));
    });
    $("box_damping").addEventListener("input", onBoxChange);
    $("show-robust-kmax").addEventListener("change", () => {
      $("robust-kmax-inputs").classList.toggle("hidden", !$("show-robust-kmax").checked);
      robustKmaxAfterRegion(); writeUrl(); updateExports();
    });
  }
  function readRobustKmaxUrl(q) {
    setBoxString(q.get("box") || boxDefault());
    $("box_damping").value = q.has("box_damping") && isFinite(Number(q.get("box_damping"))) ? q.get("box_damping") : "0";
    $("robust-kmax-inputs").classList.toggle("hidden", !$("show-robust-kmax").checked);
  }
  // The box's parameters as the server names them, keeping the rows' choices.
  function setBoxParams(list) {
    if (!Array.isArray(list) || !list.length) return;
    const box = boxString();
    BOX.params = list;
    setBoxString(box);
  }
