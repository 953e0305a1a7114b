//! The crate's axes and units mapped to those of common engines and tools.

/// An engine or content tool whose axes and units differ from (or match) the crate's, with the
/// conversion of positions and directions into its frame.
///
/// The crate's frame is right-handed with **y up**, the sea surface in the (x, z) plane, in
/// metres — the frame of glTF. Each engine gets one fixed, documented mapping:
///
/// | engine | handedness, up, unit | crate (x, y, z) → engine | texture rows | normal-map green |
/// |---|---|---|---|---|
/// | Bevy | right, +Y, m | (x, y, z) | first row at v = 0 (top) | OpenGL (+Y) |
/// | Godot | right, +Y, m | (x, y, z) | first row at v = 0 (top) | OpenGL (+Y) |
/// | Houdini | right, +Y, m | (x, y, z) | first row at v = 1 (top; v up) | OpenGL (+Y) |
/// | Unity | left, +Y, m | (x, y, −z) | first row at v = 1 (top; v up) | OpenGL (+Y) |
/// | Unreal | left, +Z, cm | 100·(x, z, y) | first row at v = 0 (top) | DirectX (−Y) |
/// | Blender | right, +Z, m | (x, −z, y) | first row at v = 1 (top; v up) | OpenGL (+Y) |
///
/// Unity and Unreal are left-handed, so their mappings are mirror images (determinant −1),
/// not rotations; Blender's is the rotation by +90° about x that its glTF importer uses.
/// "Texture rows" says where the first row of an image file (the top row of a PNG or EXR, the
/// crate's texel row j = 0, at z = 0) lands in the engine's texture coordinates: with the
/// origin at the top, world point (x, z) of a tile of side L and N texels is sampled at
/// uv = (x/L + ½/N, z/L + ½/N) (texel centres sit at (i + ½)/N); with it at the bottom, at
/// uv = (x/L + ½/N, 1 − z/L − ½/N) (or flip the image on import). Data uploaded straight to a
/// GPU API (wgpu, Vulkan, Direct3D, Metal, OpenGL) puts the first row at v = 0 in every API,
/// so uv = (x/L + ½/N, z/L + ½/N) there. The green column is the tangent-space normal-map convention each
/// engine expects by default.
///
/// ```
/// use ocean_fft::gpu::Engine;
/// // A point 2 m above the water at (x, z) = (10, 3) m, in Unreal's centimetres, z up:
/// assert_eq!(Engine::Unreal.position([10.0, 2.0, 3.0]), [1000.0, 300.0, 200.0]);
/// // The up direction is each engine's up.
/// assert_eq!(Engine::Blender.direction([0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]);
/// // And back.
/// assert_eq!(Engine::Unity.position_to_crate([1.0, 2.0, -3.0]), [1.0, 2.0, 3.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Engine {
    /// Bevy: right-handed, +Y up, metres (the crate's frame).
    Bevy,
    /// Godot: right-handed, +Y up, metres (the crate's frame).
    Godot,
    /// Houdini: right-handed, +Y up, metres (the crate's frame).
    Houdini,
    /// Unity: left-handed, +Y up, metres; the crate's z is negated.
    Unity,
    /// Unreal Engine: left-handed, +Z up, centimetres; the crate's (x, z) plane becomes
    /// Unreal's (X, Y) ground plane.
    Unreal,
    /// Blender: right-handed, +Z up, metres; the crate's z becomes Blender's −Y.
    Blender,
}

/// Signed axis permutation: engine axis e takes crate axis `AXIS[e]` times `SIGN[e]`.
struct Mapping {
    axis: [usize; 3],
    sign: [f32; 3],
    units_per_metre: f64,
}

impl Engine {
    /// Every engine, in the table's order.
    pub const ALL: [Engine; 6] = [
        Engine::Bevy,
        Engine::Godot,
        Engine::Houdini,
        Engine::Unity,
        Engine::Unreal,
        Engine::Blender,
    ];

    /// The engine's name, for menus and messages.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Bevy => "Bevy",
            Engine::Godot => "Godot",
            Engine::Houdini => "Houdini",
            Engine::Unity => "Unity",
            Engine::Unreal => "Unreal Engine",
            Engine::Blender => "Blender",
        }
    }

    fn mapping(self) -> Mapping {
        let (axis, sign, units_per_metre) = match self {
            Engine::Bevy | Engine::Godot | Engine::Houdini => ([0, 1, 2], [1.0, 1.0, 1.0], 1.0),
            Engine::Unity => ([0, 1, 2], [1.0, 1.0, -1.0], 1.0),
            Engine::Unreal => ([0, 2, 1], [1.0, 1.0, 1.0], 100.0),
            Engine::Blender => ([0, 2, 1], [1.0, -1.0, 1.0], 1.0),
        };
        Mapping {
            axis,
            sign,
            units_per_metre,
        }
    }

    /// Engine length units per metre: 100 for Unreal (centimetres), 1 otherwise.
    pub fn units_per_metre(self) -> f64 {
        self.mapping().units_per_metre
    }

    /// Whether the engine's frame is right-handed (Unity and Unreal are left-handed).
    pub fn right_handed(self) -> bool {
        !matches!(self, Engine::Unity | Engine::Unreal)
    }

    /// Whether the first row of an image file lands at the top of the engine's texture
    /// coordinates with v = 0 there (true), or with v = 1 there because v runs up (false).
    pub fn texture_origin_top(self) -> bool {
        matches!(self, Engine::Bevy | Engine::Godot | Engine::Unreal)
    }

    /// Whether the engine's tangent-space normal maps are DirectX-style (green pointing
    /// down the image, −Y) rather than OpenGL-style (+Y): true only for Unreal.
    pub fn directx_normal_maps(self) -> bool {
        matches!(self, Engine::Unreal)
    }

    /// A direction (a normal, a displacement, a velocity) `[x, y, z]` in the crate's frame,
    /// in the engine's frame. Lengths are unchanged: directions carry no unit scale (scale a
    /// displacement in metres by [`units_per_metre`](Self::units_per_metre) yourself, or
    /// use [`position`](Self::position)).
    pub fn direction(self, v: [f32; 3]) -> [f32; 3] {
        let m = self.mapping();
        std::array::from_fn(|e| m.sign[e] * v[m.axis[e]])
    }

    /// A direction in the engine's frame, in the crate's: the inverse of
    /// [`direction`](Self::direction).
    pub fn direction_to_crate(self, v: [f32; 3]) -> [f32; 3] {
        let m = self.mapping();
        let mut out = [0.0; 3];
        for e in 0..3 {
            out[m.axis[e]] = m.sign[e] * v[e];
        }
        out
    }

    /// A position `[x, y, z]` in metres in the crate's frame, in the engine's frame and
    /// units. In f64, as world positions are everywhere in the crate (the product is exact
    /// scaling; finite for any position within ±1e306 m).
    pub fn position(self, p: [f64; 3]) -> [f64; 3] {
        let m = self.mapping();
        std::array::from_fn(|e| f64::from(m.sign[e]) * p[m.axis[e]] * m.units_per_metre)
    }

    /// A position in the engine's frame and units, in metres in the crate's frame: the
    /// inverse of [`position`](Self::position) (for querying the ocean under an engine
    /// object: [`Water::height_at`](crate::Water::height_at) takes the crate's x and z).
    pub fn position_to_crate(self, p: [f64; 3]) -> [f64; 3] {
        let m = self.mapping();
        let mut out = [0.0; 3];
        for e in 0..3 {
            out[m.axis[e]] = f64::from(m.sign[e]) * p[e] / m.units_per_metre;
        }
        out
    }
}
