"""``micropillar pack``: the offline explorer's file (its size bound, what it holds, the
CLI's errors). The page itself is tested in tests/browser/test_offline_pack.py."""
from __future__ import annotations

import json
import re

from app.offline.pack import MAX_BYTES
from model.cli import main
from model.controls import CONTROLS


def test_pack_writes_one_self_contained_file_within_the_bound(tmp_path, capsys):
    import panel  # noqa: F401  -- registers models whose scripts Bokeh would add by address
    out = tmp_path / "explorer.html"
    assert main(["pack", "--out", str(out)]) == 0
    assert "wrote" in capsys.readouterr().out
    html = out.read_text(encoding="utf-8")
    assert 0 < out.stat().st_size <= MAX_BYTES
    # Nothing loaded from elsewhere: no script, link or image by address (in the markup;
    # the scripts' own text is theirs).
    markup = re.sub(r"(<script[^>]*>).*?</script>", r"\1</script>", html, flags=re.S | re.I)
    assert not re.search(r"<(script|link|img|iframe)[^>]+(src|href)=", markup, re.I)
    assert "connect-src" not in html and "default-src 'none'" in html  # requests refused
    assert 'id="mp-kernel"' in html and "MicropillarKernel" in html
    config = json.loads(re.search(r'<script id="mp-config" type="application/json">\n(.*?)\n'
                                  r'</script>', html, re.S).group(1))
    assert config["controls"]["k_r"]["lo"] == CONTROLS["k_r"].interval.lo
    assert config["controls"]["F_N"]["default"] == CONTROLS["F_N"].default


def test_pack_refuses_a_missing_folder(tmp_path, capsys):
    assert main(["pack", "--out", str(tmp_path / "no" / "explorer.html")]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "does not exist" in err
    assert main(["pack", "--out", str(tmp_path)]) == 2
    assert "is a folder" in capsys.readouterr().err


def test_the_offline_explorers_modules_are_small():
    """Each module of the offline explorer (its page scripts, the kernel and the Python
    that packs them) stays within the project's 400 lines, one concept each."""
    from importlib import resources

    here = resources.files("app.offline")
    sizes = {p.name: len(p.read_text(encoding="utf-8").splitlines())
             for p in here.iterdir() if p.name.endswith((".js", ".py"))}
    assert {"page.js", "kernel.js", "pack.py"} <= set(sizes)
    assert {name: n for name, n in sizes.items() if n > 400} == {}


def _objects(rep, out):
    """The models (``{"type": "object", ...}``) in a BokehJS JSON value, by id."""
    if isinstance(rep, dict):
        if rep.get("type") == "object" and "id" in rep:
            out[rep["id"]] = rep
        for value in rep.values():
            _objects(value, out)
    elif isinstance(rep, list):
        for value in rep:
            _objects(value, out)
    return out


def test_the_page_opens_with_the_support_tabs_models_alone(tmp_path):
    """The opening document holds the controls, the texts and the support tab; the polar
    and map tabs' panels are in ``#mp-later`` (added when first shown), sharing no model
    with it, their figures named and marked for screen readers."""
    from app.offline.pack import write
    from app.offline.tabs import LATER_ID
    out = tmp_path / "explorer.html"
    write(out)
    html = out.read_text(encoding="utf-8")
    docs = re.search(r'<script type="application/json" id="[^"]+">\s*(.*?)\s*</script>',
                     html, re.S).group(1)
    (doc,) = json.loads(docs.replace("&lt;", "<").replace("&gt;", ">")
                        .replace("&amp;", "&")).values()
    later = json.loads(re.search(rf'<script id="{LATER_ID}" type="application/json">\n(.*?)'
                                 r'\n</script>', html, re.S).group(1))
    assert set(later) == {"polar", "map"}
    opening = _objects(doc["roots"], {})
    tabs = next(r for r in doc["roots"] if r["attributes"].get("name") == "tabs")
    panels = tabs["attributes"]["tabs"]
    support = _objects(panels[0], {})
    others = _objects([r for r in doc["roots"] if r is not tabs], {})
    # The opening document: the other roots, the support tab, the Tabs (with its callback)
    # and the two placeholder panels with their placeholders -- nothing more.
    assert [p["attributes"]["name"] for p in panels] == [
        "tab-support", "tab-polar-later", "tab-map-later"]
    placeholders = _objects(panels[1:], {})
    assert sorted(m["name"] for m in placeholders.values()) == ["Div", "Div", "TabPanel", "TabPanel"]
    own = _objects({k: v for k, v in tabs["attributes"].items() if k != "tabs"}, {tabs["id"]: 0})
    assert set(opening) == set(others) | set(support) | set(placeholders) | set(own)
    assert len(own) <= 3, own  # the Tabs, its callback
    for key, panel in later.items():
        models = _objects(panel, {})
        assert not set(models) & set(opening), key
        names = {m.get("attributes", {}).get("name") for m in models.values()}
        assert panel["attributes"]["name"] == f"tab-{key}"
        want = {"polar_FTx", "polar_DyDx", "polar_FTy", "polar-status"} if key == "polar" \
            else {"regime_map", "regime_now", "map-note", "map-quantity"}
        assert want <= names, (key, names)
        figures = [m for m in models.values() if m["name"] == "Figure"]
        assert figures and all(f"figure-{f['attributes']['name']}" in
                               f["attributes"]["css_classes"] for f in figures), key


def test_a_contacts_new_data_leave_the_legends_and_the_colour_bar_alone():
    """The support's legends name still stand-ins (one NaN row, the plotted glyph), kept in
    one hidden group per figure (not painted with the plot), never a renderer of a
    contact's data: a BokehJS legend draws its entries anew when their renderers' data
    change. The top view's colour bar has a mapper of its own, equal to the path's (its
    image is redrawn whenever its mapper maps new data)."""
    import math

    from bokeh.models import ColorBar, GlyphRenderer, Span

    from app.offline.figures import support_figures

    figs = support_figures()
    for name in ("scene", "forces"):
        fig = figs[name]
        plotted = [r for r in fig.renderers if isinstance(r, GlyphRenderer)]
        groups = [r for r in fig.renderers if isinstance(r, Span) and r.name == f"{name}_legend_keys"]
        assert len(groups) == 1 and groups[0].visible is False
        for item in (i for legend in fig.legend for i in legend.items):
            for r in item.renderers:
                assert r.data_source.name is None and r in groups[0].renderers, item.label
                assert all(math.isnan(v) for col in r.data_source.data.values() for v in col)
                assert any(p.glyph is r.glyph for p in plotted) or name == "scene"
    scene = figs["scene"]
    bar = next(m for m in scene.right if isinstance(m, ColorBar))
    orbit = next(r for r in scene.renderers if isinstance(r, GlyphRenderer)
                 and r.data_source.name == "orbit")
    path_mapper = orbit.glyph.line_color.transform
    assert bar.color_mapper is not path_mapper
    assert (bar.color_mapper.palette, bar.color_mapper.low, bar.color_mapper.high) == (
        path_mapper.palette, path_mapper.low, path_mapper.high)
