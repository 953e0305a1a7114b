//! ocean-fft's real-time viewer: the default sea (or any preset) in a window, drawn with the
//! crate's reference WGSL shader (shaders/), on a clipmap to the horizon, with panels for
//! every sea-state parameter, floating bodies moved by CPU queries and a timing HUD. The
//! simulation runs on a thread of its own: the step of frame n + 1 runs while frame n
//! renders.
//!
//! ```text
//! cargo run --release -p ocean-fft-viewer
//! cargo run --release -p ocean-fft-viewer -- --preset storm
//! cargo run --release -p ocean-fft-viewer -- --frames 60 --screenshot out/viewer.png
//! ```
//!
//! viewer/README.md lists the controls and flags.

mod args;
mod bodies;
mod camera;
mod capture;
#[cfg(test)]
mod foam_gpu_tests;
mod gpu;
mod light;
mod sea;
#[cfg(test)]
mod shader_tests;
mod ui;

use std::sync::Arc;
use std::time::Instant;

use glam::Vec3;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use args::Options;
use bodies::Fleet;
use camera::Camera;
use capture::save_capture;
use gpu::{Bodies, Renderer, View};
use ocean_fft::{DepthMap, Hull};
use ocean_fft_render::{terrain, wake_centre, OceanInfo, SeaSettings, Simulation};
use ui::{Controls, Hud};

fn main() {
    // clap's: the help and exit 0 after --help, its error and exit 2 on a bad command line.
    let options = Options::parse();
    let event_loop = match EventLoop::new() {
        Ok(event_loop) => event_loop,
        Err(e) => {
            eprintln!("ocean-fft-viewer: no window system: {e}");
            std::process::exit(1);
        }
    };
    event_loop.set_control_flow(ControlFlow::Poll);
    let mut app = App {
        options,
        state: None,
        exit: Ok(()),
    };
    if let Err(e) = event_loop.run_app(&mut app) {
        eprintln!("ocean-fft-viewer: {e}");
        std::process::exit(1);
    }
    if let Err(message) = app.exit {
        eprintln!("ocean-fft-viewer: {message}");
        std::process::exit(1);
    }
}

struct App {
    options: Options,
    state: Option<State>,
    exit: Result<(), String>,
}

/// Everything that lives while the window does.
struct State {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    device: wgpu::Device,
    queue: wgpu::Queue,
    renderer: Renderer,
    egui: egui_winit::State,
    egui_renderer: egui_wgpu::Renderer,
    sim: Simulation,
    /// The frame on screen (its info and query results), kept for the panels.
    info: OceanInfo,
    camera: Camera,
    fleet: Fleet,
    queries: Vec<[f64; 2]>,
    /// The boats' hulls handed to the wake each frame.
    hulls: Vec<Hull>,
    controls: Controls,
    /// The sea last sent to the simulation, and whether its depth map was on.
    applied: sea::SeaParams,
    applied_coast: Option<bool>,
    /// The coast's depth map (`--coast`), shared with the simulation's settings.
    depth_map: Option<Arc<DepthMap>>,
    hud: Hud,
    frames: usize,
    last: Instant,
    /// Sums over the headless run (frame, step, upload = pack + write, query, wait) and the
    /// frames they cover.
    totals: [f64; 5],
    counted: usize,
    dragging: Option<(f64, f64)>,
    button: bool,
    water_under_eye: f32,
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.state.is_some() {
            return;
        }
        match State::new(event_loop, &self.options) {
            Ok(state) => self.state = Some(state),
            Err(message) => {
                self.exit = Err(message);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(state) = self.state.as_mut() else {
            return;
        };
        let consumed = state.egui.on_window_event(&state.window, &event).consumed;
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                state.config.width = size.width.max(1);
                state.config.height = size.height.max(1);
                state.surface.configure(&state.device, &state.config);
            }
            WindowEvent::KeyboardInput { event, .. } if !consumed => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    let pressed = event.state == ElementState::Pressed;
                    if !state.camera.key(code, pressed) && pressed {
                        match code {
                            KeyCode::Escape => event_loop.exit(),
                            KeyCode::Tab => {
                                state.controls.show_panels = !state.controls.show_panels
                            }
                            KeyCode::KeyP => state.controls.paused = !state.controls.paused,
                            _ => {}
                        }
                    }
                }
            }
            WindowEvent::MouseInput {
                state: button_state,
                button,
                ..
            } => {
                if matches!(button, MouseButton::Left | MouseButton::Right) {
                    state.button = button_state == ElementState::Pressed && !consumed;
                    if !state.button {
                        state.dragging = None;
                    }
                }
            }
            WindowEvent::CursorMoved { position, .. } if state.button => {
                if let Some((x, y)) = state.dragging {
                    state
                        .camera
                        .look((position.x - x) as f32, (position.y - y) as f32);
                }
                state.dragging = Some((position.x, position.y));
            }
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                state.camera.zoom_speed(lines);
            }
            WindowEvent::RedrawRequested => match state.frame(&self.options) {
                Ok(false) => {}
                Ok(true) => event_loop.exit(),
                Err(message) => {
                    self.exit = Err(message);
                    event_loop.exit();
                }
            },
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(state) = self.state.as_ref() {
            state.window.request_redraw();
        }
    }
}

impl State {
    fn new(event_loop: &ActiveEventLoop, options: &Options) -> Result<State, String> {
        let window = event_loop
            .create_window(
                Window::default_attributes()
                    .with_title("ocean-fft viewer")
                    .with_inner_size(winit::dpi::PhysicalSize::new(options.width, options.height)),
            )
            .map_err(|e| format!("window: {e}"))?;
        let window = Arc::new(window);
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle_from_env(
                Box::new(event_loop.owned_display_handle()),
            ));
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| format!("surface: {e}"))?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            compatible_surface: Some(&surface),
            force_fallback_adapter: false,
            ..Default::default()
        }))
        .map_err(|e| format!("no GPU adapter: {e}"))?;
        let adapter_info = adapter.get_info();
        eprintln!(
            "adapter: {} ({:?}, {:?}, driver {} {})",
            adapter_info.name,
            adapter_info.device_type,
            adapter_info.backend,
            adapter_info.driver,
            adapter_info.driver_info
        );
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("ocean-fft viewer"),
            required_features: wgpu::Features::empty(),
            required_limits: wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
            ..Default::default()
        }))
        .map_err(|e| format!("device: {e}"))?;

        let capabilities = surface.get_capabilities(&adapter);
        // A linear format for the window (egui draws in gamma space) with its sRGB twin as a
        // view format for the scene, which writes linear radiance.
        let format = capabilities
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                )
            })
            .unwrap_or(capabilities.formats[0].remove_srgb_suffix());
        let present_mode = if options.frames.is_some() || !options.vsync {
            wgpu::PresentMode::AutoNoVsync
        } else {
            wgpu::PresentMode::AutoVsync
        };
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode,
            desired_maximum_frame_latency: 2,
            alpha_mode: capabilities.alpha_modes[0],
            view_formats: vec![format.add_srgb_suffix()],
            color_space: Default::default(),
        };
        surface.configure(&device, &config);
        let (msaa, anisotropy) = options.quality_for(adapter_info.device_type);
        eprintln!("msaa {msaa}, anisotropy {anisotropy}");
        let mut renderer = Renderer::new(
            &device,
            format.add_srgb_suffix(),
            msaa,
            options.mesh,
            anisotropy,
        );
        let depth_map = options.coast.map(|coast| Arc::new(coast.depth_map()));
        if let Some(map) = &depth_map {
            renderer.set_terrain(&device, Some(&terrain(map)));
        }
        let egui_ctx = egui::Context::default();
        let egui = egui_winit::State::new(
            egui_ctx,
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(device.limits().max_texture_dimension_2d as usize),
        );
        let egui_renderer =
            egui_wgpu::Renderer::new(&device, format, egui_wgpu::RendererOptions::default());

        let sea = options.sea.clone();
        let spectrum = sea.spectrum().map_err(|e| format!("sea: {e}"))?;
        let mut fleet = Fleet::new(
            options.camera,
            options.heading,
            options.bodies,
            options.boat_speed,
        );
        let queries = fleet.queries(options.camera);
        let sim = Simulation::start(
            SeaSettings {
                spectrum,
                config: sea.config(),
                transition_seconds: 10.0,
                depth_map: depth_map.clone(),
            },
            options.time,
            options.pre_roll,
            options.threads,
            &queries,
        )?;
        let camera = Camera::new(
            options.camera,
            options.heading.to_radians(),
            options.pitch.to_radians(),
            options.fov.to_radians(),
        );
        let controls = Controls {
            sea: sea.clone(),
            transition: 10.0,
            light: options.light,
            render: options.render,
            time_scale: options.time_scale,
            paused: false,
            show_panels: !options.hide_ui,
            error: None,
            boat_speed: options.boat_speed,
            boats: options.bodies,
            coast: controls_coast(&depth_map),
        };
        let adapter_name: &'static str = Box::leak(
            format!("{} ({:?})", adapter_info.name, adapter_info.backend).into_boxed_str(),
        );
        Ok(State {
            window,
            surface,
            config,
            device,
            queue,
            renderer,
            egui,
            egui_renderer,
            sim,
            info: OceanInfo::default(),
            camera,
            fleet,
            queries,
            hulls: Vec::new(),
            controls,
            applied: sea,
            applied_coast: controls_coast(&depth_map),
            depth_map,
            hud: Hud {
                adapter: adapter_name,
                ..Hud::default()
            },
            frames: 0,
            last: Instant::now(),
            totals: [0.0; 5],
            counted: 0,
            dragging: None,
            button: false,
            water_under_eye: 0.0,
        })
    }

    /// The sea the panels ask for, if it changed (once no slider is being dragged): the
    /// simulation takes it live or builds a new ocean (`SeaSettings::plan`).
    fn sea_change(&mut self) -> Option<SeaSettings> {
        let edited = &self.controls.sea;
        let same = *edited == self.applied && self.controls.coast == self.applied_coast;
        if same || self.egui.egui_ctx().egui_is_using_pointer() {
            return None;
        }
        let spectrum = match edited.spectrum() {
            Ok(spectrum) => spectrum,
            Err(e) => {
                self.controls.error = Some(e.to_string());
                return None;
            }
        };
        self.controls.error = None;
        self.applied = edited.clone();
        self.applied_coast = self.controls.coast;
        Some(SeaSettings {
            spectrum,
            config: edited.config(),
            transition_seconds: f64::from(self.controls.transition),
            depth_map: self
                .depth_map
                .clone()
                .filter(|_| self.controls.coast == Some(true)),
        })
    }

    /// Draws one frame; whether the headless run is over.
    fn frame(&mut self, options: &Options) -> Result<bool, String> {
        let start = Instant::now();
        let elapsed = start.duration_since(self.last).as_secs_f64();
        let real_dt = elapsed.min(0.25);
        self.last = start;
        let headless = options.frames.is_some();
        let sea_dt = if headless {
            1.0 / 30.0
        } else if self.controls.paused {
            0.0
        } else {
            real_dt * f64::from(self.controls.time_scale)
        };

        // Frame n's data; the step of frame n + 1 starts now, on the simulation thread.
        let change = self.sea_change();
        self.fleet
            .write_queries(self.camera.position, &mut self.queries);
        self.fleet.speed = self.controls.boat_speed;
        if self.applied.wakes {
            self.fleet.hulls(&mut self.hulls);
            let side = sea::wake_config().spacing * sea::wake_config().size as f32;
            let eye = self.camera.position.to_array();
            let centre = wake_centre(eye, self.camera.forward().to_array(), side);
            self.sim.set_wake(centre, &self.hulls);
        }
        let frame = self.sim.next(sea_dt, change, &self.queries)?;
        let wait = start.elapsed().as_secs_f64() * 1e3;
        if let Some(error) = &frame.error {
            self.controls.error = Some(error.clone());
        }
        let upload_start = Instant::now();
        self.renderer.upload(&self.device, &self.queue, &frame);
        let upload = upload_start.elapsed().as_secs_f64() * 1e3;
        self.info = frame.info;
        self.water_under_eye = self.fleet.place(&frame.samples, sea_dt as f32);
        if options.follow {
            let [dx, dz] = self.fleet.lead_moved;
            self.camera.position += Vec3::new(dx, 0.0, dz);
        }
        if options.deck {
            if let Some((stern, heading)) = self.fleet.stern() {
                self.camera.position = stern + Vec3::Y * 3.0;
                self.camera.yaw = heading + std::f32::consts::PI;
            }
        }
        let times = frame.times;
        self.sim.give_back(frame);

        if !headless {
            self.camera.update(real_dt as f32, self.water_under_eye);
        } else {
            self.camera.clamp_height(self.water_under_eye);
        }
        let light = self.controls.light.light();
        let view = View {
            eye: self.camera.position,
            forward: self.camera.forward(),
            fov_y: self.camera.fov_y,
            height_above_water: self.camera.position.y - self.water_under_eye,
        };
        let size = (self.config.width, self.config.height);
        self.hud.size = size;
        self.hud.rings = self.renderer.rings_drawn;

        let surface_texture = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&self.device, &self.config);
                return Ok(false);
            }
            _ => return Ok(false),
        };
        let last = options.frames.is_some_and(|n| self.frames + 1 >= n);
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let scene_view = surface_texture
            .texture
            .create_view(&wgpu::TextureViewDescriptor {
                format: Some(self.renderer.scene_format),
                ..Default::default()
            });
        let plain_view = surface_texture.texture.create_view(&Default::default());
        let globals = self.renderer.globals(
            &self.info,
            &view,
            (&light, self.controls.light.exposure),
            &self.controls.render,
            size,
        );
        let bodies = Bodies {
            buoys: self.fleet.buoys(),
            boats: self.fleet.boats(),
        };
        self.renderer.draw(
            (&self.device, &self.queue),
            &mut encoder,
            (&scene_view, size),
            &globals,
            &bodies,
        );
        let egui_output = if self.controls.show_panels || !headless {
            let input = self.egui.take_egui_input(&self.window);
            let (controls, hud, info) = (&mut self.controls, &self.hud, &self.info);
            let output = self
                .egui
                .egui_ctx()
                .clone()
                .run_ui(input, |ui| ui::draw(ui, controls, hud, info));
            self.egui
                .handle_platform_output(&self.window, output.platform_output.clone());
            Some(output)
        } else {
            None
        };
        let paint = egui_output.map(|output| {
            let jobs = self
                .egui
                .egui_ctx()
                .tessellate(output.shapes, output.pixels_per_point);
            for (id, deltas) in &output.textures_delta.set {
                for delta in deltas {
                    self.egui_renderer
                        .update_texture(&self.device, &self.queue, *id, delta);
                }
            }
            let screen = egui_wgpu::ScreenDescriptor {
                size_in_pixels: [size.0, size.1],
                pixels_per_point: output.pixels_per_point,
            };
            self.egui_renderer.update_buffers(
                &self.device,
                &self.queue,
                &mut encoder,
                &jobs,
                &screen,
            );
            (jobs, screen, output.textures_delta.free.clone())
        });
        if let Some((jobs, screen, _)) = &paint {
            ui::paint(
                &mut self.egui_renderer,
                &mut encoder,
                &plain_view,
                (jobs, screen),
            );
        }
        let capture = if last {
            options.screenshot.as_ref().map(|_| {
                self.capture(
                    &mut encoder,
                    size,
                    &globals,
                    paint.as_ref().map(|(j, s, _)| (j, s)),
                )
            })
        } else {
            None
        };
        self.queue.submit([encoder.finish()]);
        self.queue.present(surface_texture);
        if let Some((_, _, free)) = paint {
            for id in &free {
                self.egui_renderer.free_texture(id);
            }
        }

        let frame_ms = start.elapsed().as_secs_f64() * 1e3;
        self.hud.add(frame_ms, wait, times.pack + upload, times);
        self.hud.upload = upload;
        self.frames += 1;
        // Short runs (two frames or fewer to count) count every frame.
        let short = options.frames.is_some_and(|n| n <= 3);
        if headless && (short || (self.frames > 1 && capture.is_none())) {
            // The first frame holds the start-up (pipelines, first upload) and the last the
            // screenshot's second rendering: both left out.
            self.counted += 1;
            self.totals[0] += elapsed * 1e3;
            self.totals[1] += times.step;
            self.totals[2] += times.pack + upload;
            self.totals[3] += times.query;
            self.totals[4] += wait;
        }
        if let Some((buffer, padded, (width, height))) = capture {
            let path = options.screenshot.as_ref().expect("a capture has a path");
            let bgra = self.config.format.remove_srgb_suffix() == wgpu::TextureFormat::Bgra8Unorm;
            save_capture(&self.device, &buffer, padded, width, height, bgra, path)?;
        }
        if let Some(n) = options.frames {
            if self.frames >= n {
                let counted = self.counted.max(1) as f64;
                println!(
                    "frames {n}, mean frame {:.2} ms, step {:.2} ms, upload {:.2} ms, query {:.3} ms, \
                     wait {:.2} ms",
                    self.totals[0] / counted,
                    self.totals[1] / counted,
                    self.totals[2] / counted,
                    self.totals[3] / counted,
                    self.totals[4] / counted
                );
                return Ok(true);
            }
        }
        Ok(false)
    }
}

/// The coast toggle's state for a coast's map: on when there is one.
fn controls_coast(map: &Option<Arc<DepthMap>>) -> Option<bool> {
    map.as_ref().map(|_| true)
}

/// The default eye: 2 m + 1.5 H_s above the water (at most 12 m), at the origin.
pub fn default_eye(significant_wave_height: f32) -> Vec3 {
    Vec3::new(0.0, (2.0 + 1.5 * significant_wave_height).min(12.0), 0.0)
}
