//! The panels (sea state, presets, light, time, rendering) and the timing HUD.

use egui::{Slider, Ui};

use crate::gpu::RenderSettings;
use crate::light::LightSettings;
use crate::sea::{Model, SeaParams, SPREADINGS};
use ocean_fft_render::{OceanInfo, SimTimes};

/// Everything the panels change.
pub struct Controls {
    /// The sea as edited.
    pub sea: SeaParams,
    /// Seconds of simulated time over which a change of weather happens.
    pub transition: f32,
    pub light: LightSettings,
    pub render: RenderSettings,
    /// Sea seconds per real second, and pause.
    pub time_scale: f32,
    pub paused: bool,
    pub show_panels: bool,
    /// The last error of a change of sea.
    pub error: Option<String>,
    /// The boats' speed, m/s (and whether there are boats).
    pub boat_speed: f32,
    pub boats: bool,
    /// With a coast (`--coast`): whether its depth map acts on the waves (the ground stays).
    pub coast: Option<bool>,
}

/// Smoothed timings for the HUD, ms.
#[derive(Debug, Clone, Copy, Default)]
pub struct Hud {
    pub frame: f64,
    pub wait: f64,
    pub upload: f64,
    pub sim: SimTimes,
    pub fps: f64,
    pub rings: (usize, usize),
    pub adapter: &'static str,
    pub size: (u32, u32),
}

impl Hud {
    /// Exponential smoothing over about 20 frames.
    pub fn add(&mut self, frame: f64, wait: f64, upload: f64, sim: SimTimes) {
        let a = 0.05;
        let mix = |old: f64, new: f64| {
            if old == 0.0 {
                new
            } else {
                old + a * (new - old)
            }
        };
        self.frame = mix(self.frame, frame);
        self.wait = mix(self.wait, wait);
        self.upload = mix(self.upload, upload);
        self.sim.step = mix(self.sim.step, sim.step);
        self.sim.pack = mix(self.sim.pack, sim.pack);
        self.sim.query = mix(self.sim.query, sim.query);
        self.fps = 1000.0 / self.frame.max(1e-3);
    }
}

/// A slider whose value is applied when it is released (the panel sends the change then).
fn slider(ui: &mut Ui, value: &mut f32, range: std::ops::RangeInclusive<f32>, text: &str) {
    ui.add(Slider::new(value, range).text(text));
}

fn log_slider(ui: &mut Ui, value: &mut f32, range: std::ops::RangeInclusive<f32>, text: &str) {
    ui.add(Slider::new(value, range).logarithmic(true).text(text));
}

/// Draws the panels and the HUD.
pub fn draw(ui: &mut Ui, controls: &mut Controls, hud: &Hud, info: &OceanInfo) {
    let ctx = ui.ctx().clone();
    egui::Window::new("timing")
        .anchor(egui::Align2::RIGHT_TOP, [-8.0, 8.0])
        .resizable(false)
        .collapsible(true)
        .show(&ctx, |ui| {
            ui.monospace(format!(
                "frame  {:6.2} ms ({:.1} fps)\nstep   {:6.2} ms\nupload {:6.2} ms (pack {:.2} + write {:.2})\nquery  {:6.2} ms\nwait   {:6.2} ms (render thread for the step)",
                hud.frame,
                hud.fps,
                hud.sim.step,
                hud.sim.pack + hud.upload,
                hud.sim.pack,
                hud.upload,
                hud.sim.query,
                hud.wait
            ));
            ui.monospace(format!(
                "{}×{}, {} rings, {} k vertices\n{}\nt = {:.1} s, Hs {:.2} m, λp {:.0} m, foam {:.1} %",
                hud.size.0,
                hud.size.1,
                hud.rings.0,
                hud.rings.1 / 1000,
                hud.adapter,
                info.time,
                info.significant_wave_height,
                info.peak_wavelength,
                info.foam_total * 100.0
            ));
        });
    if !controls.show_panels {
        return;
    }
    egui::Panel::left("controls")
        .default_size(300.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| panels(ui, controls, info));
        });
}

fn panels(ui: &mut Ui, controls: &mut Controls, info: &OceanInfo) {
    ui.heading("Presets");
    ui.horizontal_wrapped(|ui| {
        for name in SeaParams::preset_names() {
            if ui.button(name).clicked() {
                if let Some(sea) = SeaParams::preset(name) {
                    controls.sea = sea;
                    controls.light.overcast = if name == "storm" { 0.85 } else { 0.0 };
                }
            }
        }
    });
    ui.separator();
    let sea = &mut controls.sea;
    ui.heading(format!("Sea ({})", sea.name));
    let mut model = sea.model.index();
    egui::ComboBox::from_label("spectrum")
        .selected_text(Model::NAMES[model])
        .show_ui(ui, |ui| {
            for (i, name) in Model::NAMES.iter().enumerate() {
                ui.selectable_value(&mut model, i, *name);
            }
        });
    if model != sea.model.index() {
        sea.model = Model::from_index(model);
        if sea.model == Model::Tma && sea.depth.is_none() {
            sea.depth = Some(20.0);
        }
    }
    match &mut sea.model {
        Model::JonswapParameters { alpha, peak_period } => {
            log_slider(ui, alpha, 1e-4..=0.05, "α");
            slider(ui, peak_period, 2.0..=25.0, "peak period Tp [s]");
        }
        Model::Elfouhaily { inverse_wave_age } => {
            slider(ui, inverse_wave_age, 0.84..=5.0, "inverse wave age Ω");
        }
        Model::Phillips { amplitude } => {
            log_slider(ui, amplitude, 1e-9..=1e-4, "amplitude");
        }
        _ => {}
    }
    slider(ui, &mut sea.wind_speed, 0.5..=40.0, "wind U10 [m/s]");
    if matches!(sea.model, Model::Jonswap | Model::Tma) {
        log_slider(ui, &mut sea.fetch, 1_000.0..=1_000_000.0, "fetch [m]");
    }
    if matches!(
        sea.model,
        Model::Jonswap | Model::Tma | Model::JonswapParameters { .. }
    ) {
        slider(ui, &mut sea.gamma, 1.0..=7.0, "peak enhancement γ");
    }
    slider(ui, &mut sea.direction, -180.0..=180.0, "wind direction [°]");
    egui::ComboBox::from_label("spreading")
        .selected_text(SPREADINGS[sea.spreading])
        .show_ui(ui, |ui| {
            for (i, name) in SPREADINGS.iter().enumerate() {
                ui.selectable_value(&mut sea.spreading, i, *name);
            }
        });
    if sea.spreading == 3 {
        log_slider(ui, &mut sea.spreading_s, 0.5..=200.0, "spreading s");
    }
    slider(ui, &mut sea.swell, 0.0..=1.0, "swell ξ");
    let mut shallow = sea.depth.is_some();
    ui.checkbox(&mut shallow, "finite depth");
    if shallow || sea.model == Model::Tma {
        let mut depth = sea.depth.unwrap_or(20.0);
        log_slider(ui, &mut depth, 1.0..=500.0, "depth [m]");
        sea.depth = Some(depth);
    } else {
        sea.depth = None;
    }
    slider(ui, &mut sea.choppiness, 0.0..=2.0, "choppiness λ");
    slider(ui, &mut sea.foam_coverage, 0.0..=5.0, "foam ×");
    slider(ui, &mut controls.transition, 0.0..=60.0, "transition [s]");
    // The grids the ocean runs: the panel's, or grids fitted to a sea they cannot hold.
    let running: Vec<f32> = info.lengths[..info.cascades]
        .iter()
        .map(|l| l.round())
        .collect();
    let asked: Vec<f32> = sea.lengths.iter().map(|l| l.round()).collect();
    if info.cascades == 0 || running == asked {
        ui.label(format!("cascades {asked:?} m, {}²", sea.size));
    } else {
        ui.label(format!(
            "cascades {running:?} m, {}² (fitted to the sea; asked {asked:?})",
            info.size
        ));
    }
    let mut size = sea.size;
    egui::ComboBox::from_label("grid N")
        .selected_text(size.to_string())
        .show_ui(ui, |ui| {
            for n in [64, 128, 256, 512] {
                ui.selectable_value(&mut size, n, n.to_string());
            }
        });
    sea.size = size;
    if let Some(error) = &controls.error {
        ui.colored_label(egui::Color32::LIGHT_RED, error);
    }
    ui.separator();

    if controls.boats {
        ui.heading("Boats");
        ui.checkbox(&mut controls.sea.wakes, "wakes");
        slider(ui, &mut controls.boat_speed, 0.0..=20.0, "speed [m/s]");
        ui.separator();
    }

    if let Some(on) = controls.coast.as_mut() {
        ui.heading("Coast");
        ui.checkbox(on, "waves feel the depth map");
        ui.separator();
    }

    ui.heading("Time");
    ui.checkbox(&mut controls.paused, "pause");
    log_slider(ui, &mut controls.time_scale, 0.05..=10.0, "time scale");
    ui.separator();

    ui.heading("Light");
    let light = &mut controls.light;
    slider(ui, &mut light.elevation, -2.0..=90.0, "sun elevation [°]");
    slider(ui, &mut light.azimuth, -180.0..=180.0, "sun azimuth [°]");
    slider(ui, &mut light.overcast, 0.0..=1.0, "overcast");
    log_slider(ui, &mut light.exposure, 0.1..=4.0, "exposure");
    log_slider(ui, &mut light.haze, 500.0..=50_000.0, "haze [m]");
    ui.separator();

    ui.heading("Rendering");
    slider(ui, &mut controls.render.tiling, 0.0..=1.0, "tiling breaker");
    slider(
        ui,
        &mut controls.render.tiling_scale,
        0.1..=3.0,
        "its cell [× L₀]",
    );
    ui.label(
        "Fly: W A S D, E/Q up/down, Shift fast, drag to look, wheel: speed. Tab hides the panels.",
    );
}

/// Draws egui's `jobs` over `target` (the window's linear view).
pub fn paint(
    renderer: &mut egui_wgpu::Renderer,
    encoder: &mut wgpu::CommandEncoder,
    target: &wgpu::TextureView,
    (jobs, screen): (&[egui::ClippedPrimitive], &egui_wgpu::ScreenDescriptor),
) {
    let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("egui"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    let mut pass = pass.forget_lifetime();
    renderer.render(&mut pass, jobs, screen);
}
