//! A scene as HTML that opens offline in any current browser: the scene document embedded as
//! JSON, three.js 0.180.0 (MIT, its licence in `three/LICENSE`; the minified `three.core.min.js`
//! and `three.module.min.js` and the orbit controls, 759 kB together) embedded as text and
//! loaded from object URLs, so that the page fetches nothing. Orbit (left drag), pan (right
//! drag), zoom (wheel), a posture selector (one at a time, or all ghosted), a legend with units
//! and a scale bar.

use super::Scene;
use std::fmt::Write;

/// three.js's licence, which the page carries.
const LICENSE: &str = include_str!("three/LICENSE");
const THREE_CORE: &str = include_str!("three/three.core.min.js");
const THREE: &str = include_str!("three/three.module.min.js");
const ORBIT: &str = include_str!("three/OrbitControls.js");
const VIEWER: &str = include_str!("viewer.js");

const STYLE: &str = "
.stiffid-scene { position: relative; font: 13px/1.4 system-ui, sans-serif; color: #222; }
.stiffid-scene .view { box-sizing: border-box; width: 100%; height: 560px; border: 1px solid #ccd; }
.stiffid-scene .controls { margin: 4px 0; }
.stiffid-scene .legend { margin-top: 4px; padding: 6px 8px; border: 1px solid #ccd; border-radius: 4px;
}
.stiffid-scene .legend .note { color: #666; font-style: italic; }
.stiffid-scene .key { display: inline-block; width: 12px; height: 12px; margin: 0 4px 0 6px;
  vertical-align: -1px; border-radius: 2px; }
.stiffid-scene .ramp { display: inline-block; width: 80px; height: 10px;
  background: linear-gradient(to right, hsl(238,85%,45%), hsl(120,85%,45%), hsl(0,85%,45%)); }
.stiffid-scene .stage { position: relative; }
.stiffid-scene .scale { position: absolute; bottom: 14px; right: 14px; background: rgba(255,255,255,0.85);
  padding: 4px 8px; border-radius: 4px; text-align: center; }
.stiffid-scene .bar { height: 6px; border: 2px solid #222; border-top: none; margin: 0 auto; }
";

/// The HTML of `scene` to put in a page (`id` names it, unique in the page; ASCII letters,
/// digits and `-`): the view, its selector, legend and scale bar, the scene's JSON, three.js
/// and the viewer. One scene per page.
pub fn fragment(scene: &Scene, id: &str) -> String {
    let json = serde_json::to_string(scene)
        .expect("a scene serialises")
        .replace("</", "<\\/");
    let mut s = String::with_capacity(json.len() + THREE_CORE.len() + THREE.len() + 60_000);
    let _ = write!(
        s,
        "<style>{STYLE}</style>\n<div class=\"stiffid-scene\" id=\"{id}\" data-scene=\"{id}-data\">\n\
         <div class=\"controls\">Posture: <select>"
    );
    for i in 1..=scene.postures.len() {
        let _ = write!(s, "<option value=\"{}\">posture {i}</option>", i - 1);
    }
    if scene.postures.len() > 1 {
        s.push_str("<option value=\"all\">all postures, ghosted</option>");
    }
    s.push_str(
        "</select> <span class=\"help\">drag: orbit, right drag: pan, wheel: zoom</span></div>\n\
         <div class=\"stage\"><div class=\"view\"></div>\n\
         <div class=\"scale\"><div class=\"bar-text\"></div><div class=\"bar\"></div></div></div>\n\
         <div class=\"legend\"></div>\n</div>\n",
    );
    let _ = writeln!(
        s,
        "<script type=\"application/json\" id=\"{id}-data\">{json}</script>"
    );
    let _ = writeln!(s, "<!-- three.js 0.180.0:\n{LICENSE}-->");
    for (name, code) in [
        ("stiffid-three-core", THREE_CORE),
        ("stiffid-three", THREE),
        ("stiffid-orbit", ORBIT),
    ] {
        let _ = writeln!(
            s,
            "<script type=\"text/plain\" id=\"{name}\">{code}</script>"
        );
    }
    let _ = writeln!(s, "<script type=\"module\">{VIEWER}</script>");
    s
}

/// A whole HTML page of `scene` titled `title` (escaped here).
pub fn page(scene: &Scene, title: &str) -> String {
    let title = escape(title);
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"generator\" content=\"stiffid scene\"><title>{title}</title></head>\n\
         <body style=\"margin: 12px\"><h1 style=\"font: 600 18px system-ui, sans-serif\">{title}</h1>\n{}</body></html>\n",
        fragment(scene, "scene")
    )
}

/// `text` with HTML's special characters escaped.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
