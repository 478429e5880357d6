//! A headless Chromium driven over the DevTools protocol, through `--remote-debugging-pipe`
//! (JSON messages ended by a NUL byte; the browser reads commands from its fd 3 and writes
//! answers and events to its fd 4). No network port and no websocket: `sh` hands the child's
//! stdin and stdout pipes to the browser as fds 3 and 4. Clicks and typing are the input
//! events a user's mouse and keyboard make (`Input.dispatchMouseEvent`, `Input.insertText`).

use super::TempDir;
use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

pub struct Browser {
    child: Child,
    to: ChildStdin,
    from: Receiver<Value>,
    next_id: u64,
    session: String,
    _profile: TempDir,
}

impl Browser {
    /// Start `chrome` headless with a fresh profile and open one blank page (`width` × `height`).
    pub fn launch(chrome: &str, width: u32, height: u32) -> Browser {
        let profile = TempDir::new("chrome-cdp");
        let mut child = Command::new("sh")
            .arg("-c")
            .arg(r#"exec "$0" "$@" 3<&0 4>&1 </dev/null >/dev/null"#)
            .arg(chrome)
            .args([
                "--headless",
                "--remote-debugging-pipe",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-quic",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--hide-scrollbars",
            ])
            .arg(format!("--window-size={width},{height}"))
            .arg(format!("--user-data-dir={}", profile.0.display()))
            .arg("about:blank")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromium");
        let to = child.stdin.take().unwrap();
        let stdout = child.stdout.take().unwrap();
        let (tx, from) = channel();
        std::thread::spawn(move || {
            let mut r = BufReader::new(stdout);
            let mut buf = Vec::new();
            while r.read_until(0, &mut buf).is_ok_and(|n| n > 0) {
                buf.pop_if(|b| *b == 0);
                if let Ok(v) = serde_json::from_slice::<Value>(&buf) {
                    if tx.send(v).is_err() {
                        break;
                    }
                }
                buf.clear();
            }
        });
        let mut b = Browser {
            child,
            to,
            from,
            next_id: 0,
            session: String::new(),
            _profile: profile,
        };
        let target = b.send(None, "Target.createTarget", json!({ "url": "about:blank" }));
        let target_id = target["targetId"].as_str().expect("a target id").to_string();
        let attached = b.send(
            None,
            "Target.attachToTarget",
            json!({ "targetId": target_id, "flatten": true }),
        );
        b.session = attached["sessionId"].as_str().expect("a session id").to_string();
        b
    }

    /// One command, and its result (panics on a protocol error or after 30 s).
    fn send(&mut self, session: Option<&str>, method: &str, params: Value) -> Value {
        self.next_id += 1;
        let id = self.next_id;
        let mut msg = json!({ "id": id, "method": method, "params": params });
        if let Some(s) = session {
            msg["sessionId"] = json!(s);
        }
        let mut bytes = serde_json::to_vec(&msg).unwrap();
        bytes.push(0);
        self.to.write_all(&bytes).expect("write to chromium");
        let t0 = Instant::now();
        loop {
            let left = Duration::from_secs(30).saturating_sub(t0.elapsed());
            match self.from.recv_timeout(left) {
                Ok(v) if v["id"] == id => {
                    assert!(v["error"].is_null(), "{method}: {}", v["error"]);
                    return v["result"].clone();
                }
                Ok(_) => {} // an event
                Err(RecvTimeoutError::Timeout) => panic!("{method}: no answer from chromium in 30 s"),
                Err(RecvTimeoutError::Disconnected) => panic!("{method}: chromium has gone"),
            }
        }
    }

    /// A command to the page.
    pub fn call(&mut self, method: &str, params: Value) -> Value {
        let session = self.session.clone();
        self.send(Some(&session), method, params)
    }

    pub fn navigate(&mut self, url: &str) {
        self.call("Page.navigate", json!({ "url": url }));
    }

    /// The value of a JavaScript expression in the page (promises awaited; panics on a throw).
    pub fn eval(&mut self, expr: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({ "expression": expr, "returnByValue": true, "awaitPromise": true }),
        );
        assert!(r["exceptionDetails"].is_null(), "{expr}: {}", r["exceptionDetails"]);
        r["result"]["value"].clone()
    }

    /// Poll `expr` until it is truthy (not null, false, 0, "" or []; a throw, e.g. while the
    /// page loads, is not yet); its value. Panics after `secs` with `show`'s value (what the
    /// page shows).
    pub fn wait_for(&mut self, expr: &str, secs: u64, show: &str) -> Value {
        let t0 = Instant::now();
        let guarded = format!("(() => {{ try {{ return ({expr}); }} catch (e) {{ return null; }} }})()");
        loop {
            let v = self.eval(&guarded);
            let truthy = !matches!(&v, Value::Null | Value::Bool(false))
                && v.as_f64() != Some(0.0)
                && v.as_str() != Some("")
                && v.as_array().is_none_or(|a| !a.is_empty());
            if truthy {
                return v;
            }
            if t0.elapsed() > Duration::from_secs(secs) {
                let shows = self.eval(&format!(
                    "(() => {{ try {{ return ({show}); }} catch (e) {{ return String(e); }} }})()"
                ));
                panic!("waited {secs} s for `{expr}`; the page shows: {shows}");
            }
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// The centre of `selector`'s element, scrolled into view; panics unless the element is
    /// displayed there and on top (a click there reaches it).
    fn centre(&mut self, selector: &str) -> (f64, f64) {
        let sel = serde_json::to_string(selector).unwrap();
        let v = self.eval(&format!(
            "(() => {{ const e = document.querySelector({sel}); if (!e) return 'no element';
               e.scrollIntoView({{ block: 'center' }}); const r = e.getBoundingClientRect();
               const x = r.x + r.width / 2, y = r.y + r.height / 2, top = document.elementFromPoint(x, y);
               if (!r.width || !r.height) return 'not displayed';
               if (top !== e && !e.contains(top) && !(top && top.control === e)) return 'covered by ' + (top && top.outerHTML.slice(0, 80));
               return [x, y]; }})()"
        ));
        match v.as_array() {
            Some(xy) => (xy[0].as_f64().unwrap(), xy[1].as_f64().unwrap()),
            None => panic!("cannot click {selector}: {v}"),
        }
    }

    /// A left click on `selector`'s element, as the mouse makes it.
    pub fn click(&mut self, selector: &str) {
        let (x, y) = self.centre(selector);
        for t in ["mouseMoved", "mousePressed", "mouseReleased"] {
            self.call(
                "Input.dispatchMouseEvent",
                json!({ "type": t, "x": x, "y": y, "button": "left", "clickCount": 1 }),
            );
        }
    }

    /// A drag with the left button from the centre of `selector`'s element by `(dx, dy)`
    /// pixels, in `steps` moves, as the mouse makes it.
    pub fn drag(&mut self, selector: &str, dx: f64, dy: f64, steps: u32) {
        let (x, y) = self.centre(selector);
        let press = json!({ "type": "mousePressed", "x": x, "y": y, "button": "left", "buttons": 1, "clickCount": 1 });
        self.call("Input.dispatchMouseEvent", press);
        for k in 1..=steps {
            let f = k as f64 / steps as f64;
            self.call(
                "Input.dispatchMouseEvent",
                json!({ "type": "mouseMoved", "x": x + f * dx, "y": y + f * dy, "button": "left", "buttons": 1 }),
            );
        }
        self.call(
            "Input.dispatchMouseEvent",
            json!({ "type": "mouseReleased", "x": x + dx, "y": y + dy, "button": "left", "buttons": 0, "clickCount": 1 }),
        );
    }

    /// Click into a text field, select what it holds and type `text` over it.
    pub fn type_into(&mut self, selector: &str, text: &str) {
        self.click(selector);
        let sel = serde_json::to_string(selector).unwrap();
        self.eval(&format!("document.querySelector({sel}).select()"));
        if text.is_empty() {
            self.call(
                "Input.dispatchKeyEvent",
                json!({ "type": "keyDown", "key": "Delete", "code": "Delete", "windowsVirtualKeyCode": 46 }),
            );
            self.call(
                "Input.dispatchKeyEvent",
                json!({ "type": "keyUp", "key": "Delete", "code": "Delete", "windowsVirtualKeyCode": 46 }),
            );
        } else {
            self.call("Input.insertText", json!({ "text": text }));
        }
    }

    /// Choose `value` in a `<select>` (focus, the option's value, a `change` event: what the
    /// drop-down does, which a headless browser does not draw).
    pub fn choose(&mut self, selector: &str, value: &str) {
        self.centre(selector);
        let sel = serde_json::to_string(selector).unwrap();
        let val = serde_json::to_string(value).unwrap();
        let chosen = self.eval(&format!(
            "(() => {{ const s = document.querySelector({sel}); s.value = {val};
               s.dispatchEvent(new Event('input', {{ bubbles: true }}));
               s.dispatchEvent(new Event('change', {{ bubbles: true }})); return s.value; }})()"
        ));
        assert_eq!(chosen.as_str(), Some(value), "{selector} has no option {value}");
    }

    /// A PNG of the page as it is drawn now: the viewport, or the box of `selector`'s element
    /// with a 16 px margin.
    pub fn screenshot(&mut self, selector: Option<&str>) -> Vec<u8> {
        let mut params = json!({ "format": "png" });
        if let Some(sel) = selector {
            let sel = serde_json::to_string(sel).unwrap();
            let r = self.eval(&format!(
                "(() => {{ const r = document.querySelector({sel}).getBoundingClientRect();
                   return {{ x: Math.max(0, r.x - 16), y: Math.max(0, r.y + scrollY - 16), width: r.width + 32, height: r.height + 32, scale: 1 }}; }})()"
            ));
            params["clip"] = r;
            params["captureBeyondViewport"] = json!(true);
        }
        let r = self.call("Page.captureScreenshot", params);
        base64_decode(r["data"].as_str().expect("screenshot data"))
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn base64_decode(s: &str) -> Vec<u8> {
    let val = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        b'/' => 63,
        _ => panic!("not base64: {c}"),
    };
    let digits: Vec<u8> = s.bytes().filter(|&c| c != b'=').map(val).collect();
    let mut out = Vec::with_capacity(digits.len() * 3 / 4);
    for chunk in digits.chunks(4) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, &d)| n | (d as u32) << (18 - 6 * i));
        out.extend_from_slice(&n.to_be_bytes()[1..chunk.len()]);
    }
    out
}
