//! A small glTF 2.0 binary (GLB) writer: one buffer, tightly packed views, accessors
//! with the bounds the specification asks for, meshes, nodes and materials; the
//! JSON is written with serde_json against the specification (Khronos glTF 2.0,
//! sections 3.6 "Binary data storage", 3.7 "Geometry", 4.4 "GLB file format").
//!
//! Every view starts on a 4-byte boundary (vertex attributes of 4-byte
//! components need no byte stride), the JSON chunk is padded with spaces and the
//! binary chunk with zeros to a multiple of 4. Output depends only on the input:
//! the same scene gives the same bytes.

use serde_json::{Map, Value, json};

/// glTF component type FLOAT.
const FLOAT: u32 = 5126;
/// glTF component type UNSIGNED_INT (indices only).
const UNSIGNED_INT: u32 = 5125;
/// Buffer view target ARRAY_BUFFER (vertex attributes).
const ARRAY_BUFFER: u32 = 34962;
/// Buffer view target ELEMENT_ARRAY_BUFFER (indices).
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// Primitive mode LINES.
pub const LINES: u32 = 1;
/// Primitive mode TRIANGLES.
pub const TRIANGLES: u32 = 4;

/// A scene being assembled (module doc).
#[derive(Debug, Default)]
pub struct Glb {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    materials: Vec<Value>,
    meshes: Vec<Value>,
    nodes: Vec<Value>,
    extras: Map<String, Value>,
}

/// Componentwise bounds of `data` taken `n` at a time.
fn bounds(data: &[f32], n: usize) -> (Vec<f32>, Vec<f32>) {
    let mut lo = vec![f32::INFINITY; n];
    let mut hi = vec![f32::NEG_INFINITY; n];
    for chunk in data.chunks_exact(n) {
        for (k, &x) in chunk.iter().enumerate() {
            lo[k] = lo[k].min(x);
            hi[k] = hi[k].max(x);
        }
    }
    (lo, hi)
}

impl Glb {
    /// An empty scene.
    pub fn new() -> Glb {
        Glb::default()
    }

    /// Appends `bytes` as a buffer view for `target`; its index.
    fn view(&mut self, bytes: &[u8], target: u32) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.views.push(json!({
            "buffer": 0,
            "byteOffset": offset,
            "byteLength": bytes.len(),
            "target": target,
        }));
        self.views.len() - 1
    }

    /// A vertex attribute of `kind` (`SCALAR`, `VEC3`, ...) with `n` floats per
    /// element; with its bounds (required for `POSITION`, written for every
    /// attribute). Its accessor index.
    pub fn floats(&mut self, data: &[f32], kind: &str, n: usize) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, ARRAY_BUFFER);
        let (min, max) = bounds(data, n);
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": data.len() / n,
            "type": kind,
            "min": min,
            "max": max,
        }));
        self.accessors.len() - 1
    }

    /// Vertex indices; their accessor index.
    pub fn indices(&mut self, data: &[u32]) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, ELEMENT_ARRAY_BUFFER);
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": UNSIGNED_INT,
            "count": data.len(),
            "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    /// A material of linear RGBA `colour`, lit (metallic-roughness) or, for lines
    /// and vertex-coloured stock, as it is; its index.
    pub fn material(&mut self, name: &str, colour: [f32; 4], metallic: f32) -> usize {
        self.materials.push(json!({
            "name": name,
            "pbrMetallicRoughness": {
                "baseColorFactor": colour,
                "metallicFactor": metallic,
                "roughnessFactor": 0.6,
            },
            "doubleSided": true,
        }));
        self.materials.len() - 1
    }

    /// A mesh of one primitive: `attributes` (semantic, accessor), `indices`,
    /// `mode` ([`LINES`], [`TRIANGLES`]) and `material`; a node named `name` holding
    /// it, with `extras`. The node's index.
    pub fn mesh_node(
        &mut self,
        name: &str,
        attributes: &[(&str, usize)],
        indices: Option<usize>,
        mode: u32,
        material: usize,
    ) -> usize {
        let attributes: Map<String, Value> = attributes
            .iter()
            .map(|&(k, a)| (k.to_string(), json!(a)))
            .collect();
        let mut primitive = json!({
            "attributes": attributes,
            "mode": mode,
            "material": material,
        });
        if let Some(i) = indices {
            primitive["indices"] = json!(i);
        }
        self.meshes
            .push(json!({ "name": name, "primitives": [primitive] }));
        self.nodes
            .push(json!({ "name": name, "mesh": self.meshes.len() - 1 }));
        self.nodes.len() - 1
    }

    /// A node named `name` with nothing in it (a set that is empty in this scene);
    /// its index.
    pub fn empty_node(&mut self, name: &str) -> usize {
        self.nodes.push(json!({ "name": name }));
        self.nodes.len() - 1
    }

    /// Sets `key` of node `node` (a translation, a rotation, extras).
    pub fn set_node(&mut self, node: usize, key: &str, value: Value) {
        self.nodes[node][key] = value;
    }

    /// Sets `key` of the scene's extras (metadata for the viewer page).
    pub fn extra(&mut self, key: &str, value: Value) {
        self.extras.insert(key.to_string(), value);
    }

    /// The glTF JSON document (without the binary chunk).
    pub fn document(&self) -> Value {
        let mut doc = json!({
            "asset": { "version": "2.0", "generator": concat!("swarf ", env!("CARGO_PKG_VERSION")) },
            "scene": 0,
            "scenes": [{ "nodes": (0..self.nodes.len()).collect::<Vec<_>>(), "extras": self.extras }],
            "nodes": self.nodes,
        });
        for (key, list) in [
            ("meshes", &self.meshes),
            ("materials", &self.materials),
            ("accessors", &self.accessors),
            ("bufferViews", &self.views),
        ] {
            if !list.is_empty() {
                doc[key] = json!(list);
            }
        }
        if !self.bin.is_empty() {
            doc["buffers"] = json!([{ "byteLength": self.padded_bin_len() }]);
        }
        doc
    }

    fn padded_bin_len(&self) -> usize {
        self.bin.len().div_ceil(4) * 4
    }

    /// The GLB file: header, JSON chunk, binary chunk (module doc).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut json = self.document().to_string().into_bytes();
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let bin_len = self.padded_bin_len();
        let chunk = |n: usize| 8 + n;
        let total = 12 + chunk(json.len()) + if bin_len > 0 { chunk(bin_len) } else { 0 };
        let mut out = Vec::with_capacity(total);
        let word = |out: &mut Vec<u8>, x: usize| out.extend_from_slice(&(x as u32).to_le_bytes());
        out.extend_from_slice(b"glTF");
        word(&mut out, 2);
        word(&mut out, total);
        word(&mut out, json.len());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json);
        if bin_len > 0 {
            word(&mut out, bin_len);
            out.extend_from_slice(b"BIN\0");
            out.extend_from_slice(&self.bin);
            out.resize(total, 0);
        }
        out
    }
}

/// Linear-light value of an sRGB byte (glTF vertex colours and colour factors are
/// linear; the PNG pictures' colours are sRGB).
pub fn linear(c: u8) -> f32 {
    let s = f64::from(c) / 255.0;
    let l = if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    };
    l as f32
}

/// The sRGB byte of a linear-light value (the inverse of [`linear`], rounded).
pub fn srgb(l: f32) -> u8 {
    let l = f64::from(l).clamp(0.0, 1.0);
    let s = if l <= 0.0031308 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_round_trip() {
        for c in 0..=255u8 {
            assert_eq!(srgb(linear(c)), c);
        }
    }

    #[test]
    fn empty_scene_is_a_glb_header_and_json() {
        let bytes = Glb::new().to_bytes();
        assert_eq!(&bytes[..4], b"glTF");
        assert!(bytes.len().is_multiple_of(4));
        assert_eq!(
            u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
            bytes.len()
        );
    }
}
