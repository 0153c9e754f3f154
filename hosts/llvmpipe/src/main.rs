//! `umbra-llvmpipe MESH.obj SIDE FRAMES`: the mesh drawn depth-only into a
//! `SIDE × SIDE` 24-bit depth buffer by the OpenGL ES implementation EGL
//! finds headless (Mesa's llvmpipe, through EGL surfaceless), from the
//! spot light that frames it ([`Perspective::framing`], the view
//! `umbra depth --mesh` draws), `FRAMES` times after one warm-up frame; it
//! prints `key=value` lines: the renderer, the triangles, whether anything
//! was drawn, and the median and fastest frame in milliseconds (clear,
//! draw, `glFinish`).
//!
//! Set `LP_NUM_THREADS=1` for one thread, as the benches do. The bench
//! `llvmpipe` drives it; install llvmpipe with
//! `apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri`.

use std::time::Instant;

use glow::HasContext;
use khronos_egl as egl;
use umbra_sim::input::limits::Limits;
use umbra_sim::world::mesh::Mesh;
use umbra_sim::world::scene::Perspective;

/// `EGL_PLATFORM_SURFACELESS_MESA`.
const PLATFORM_SURFACELESS: egl::Enum = 0x31DD;

const VERTEX: &str = "#version 300 es
uniform mat4 m;
layout(location = 0) in vec3 p;
void main() { gl_Position = m * vec4(p, 1.0); }
";
const FRAGMENT: &str = "#version 300 es
precision mediump float;
void main() {}
";

fn main() {
    if let Err(e) = run() {
        eprintln!("umbra-llvmpipe: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().collect();
    let [_, mesh, side, frames] = args.as_slice() else {
        return Err("usage: umbra-llvmpipe MESH.obj SIDE FRAMES".into());
    };
    let side: i32 = side.parse().map_err(|_| format!("SIDE `{side}` is not a number"))?;
    let frames: usize = frames.parse().map_err(|_| format!("FRAMES `{frames}` is not a number"))?;
    let mesh = Mesh::load_obj(mesh.as_ref(), &Limits::DEFAULT).map_err(|e| e.to_string())?;
    let light = Perspective::framing(&mesh).ok_or("the mesh has no vertices")?;
    // Umbra's clip depth is D3D's, z in [0, w]; GL's is [-w, w]: z' = 2z − w.
    let mut m = light.view_projection().to_cols_array_2d();
    for col in &mut m {
        col[2] = 2.0 * col[2] - col[3];
    }
    let gl = context()?;
    let (ms, passed, renderer) = draw(&gl, &mesh, &m, side, frames.max(1))?;
    let mut sorted = ms.clone();
    sorted.sort_by(f64::total_cmp);
    println!("renderer={renderer}");
    println!("triangles={}", mesh.triangles.len());
    println!("drawn={passed}");
    println!("ms_median={:.4}", sorted[sorted.len() / 2]);
    println!("ms_min={:.4}", sorted[0]);
    Ok(())
}

/// An OpenGL ES 3 context current on this thread, without a surface.
fn context() -> Result<glow::Context, String> {
    fn err(what: &'static str) -> impl Fn(egl::Error) -> String {
        move |e| format!("{what}: {e}")
    }
    // SAFETY: loads the system's libEGL and resolves its entry points; the
    // library stays loaded for the life of the instance, which this process
    // keeps (leaked below) as long as the context is used.
    #[allow(unsafe_code)]
    let egl = unsafe { egl::DynamicInstance::<egl::EGL1_5>::load_required() }
        .map_err(|e| format!("no libEGL (install libegl1 libegl-mesa0 libgl1-mesa-dri): {e}"))?;
    let egl: &'static _ = Box::leak(Box::new(egl));
    // SAFETY: the surfaceless platform takes the default display and no attributes.
    #[allow(unsafe_code)]
    let display = unsafe { egl.get_platform_display(PLATFORM_SURFACELESS, egl::DEFAULT_DISPLAY, &[egl::ATTRIB_NONE]) }
        .map_err(err("EGL surfaceless display"))?;
    egl.initialize(display).map_err(err("eglInitialize"))?;
    egl.bind_api(egl::OPENGL_ES_API).map_err(err("eglBindAPI"))?;
    let attributes = [egl::SURFACE_TYPE, egl::PBUFFER_BIT, egl::RENDERABLE_TYPE, egl::OPENGL_ES3_BIT, egl::NONE];
    let config = egl
        .choose_first_config(display, &attributes)
        .map_err(err("eglChooseConfig"))?
        .ok_or("no OpenGL ES 3 configuration")?;
    let context = egl
        .create_context(display, config, None, &[egl::CONTEXT_MAJOR_VERSION, 3, egl::NONE])
        .map_err(err("eglCreateContext"))?;
    egl.make_current(display, None, None, Some(context)).map_err(err("eglMakeCurrent"))?;
    // SAFETY: the context is current on this thread, and EGL returns entry
    // points valid for it (or none, which glow treats as missing).
    #[allow(unsafe_code)]
    let gl = unsafe {
        glow::Context::from_loader_function(|name| {
            egl.get_proc_address(name).map_or(std::ptr::null(), |f| f as *const std::ffi::c_void)
        })
    };
    Ok(gl)
}

/// Draw `mesh` depth-only with `m` into a `side²` depth texture `frames`
/// times: each frame's milliseconds, whether any fragment passed, and the
/// renderer's name.
fn draw(
    gl: &glow::Context,
    mesh: &Mesh,
    m: &[[f32; 4]; 4],
    side: i32,
    frames: usize,
) -> Result<(Vec<f64>, bool, String), String> {
    // SAFETY: every call below is on the context made current by
    // `context`, with objects this function creates and sizes it checks;
    // the buffers handed to GL outlive the calls that read them.
    #[allow(unsafe_code)]
    unsafe {
        let renderer = gl.get_parameter_string(glow::RENDERER);
        let program = gl.create_program()?;
        for (kind, source) in [(glow::VERTEX_SHADER, VERTEX), (glow::FRAGMENT_SHADER, FRAGMENT)] {
            let shader = gl.create_shader(kind)?;
            gl.shader_source(shader, source);
            gl.compile_shader(shader);
            if !gl.get_shader_compile_status(shader) {
                return Err(gl.get_shader_info_log(shader));
            }
            gl.attach_shader(program, shader);
        }
        gl.link_program(program);
        if !gl.get_program_link_status(program) {
            return Err(gl.get_program_info_log(program));
        }
        gl.use_program(Some(program));
        let flat: Vec<f32> = m.iter().flatten().copied().collect();
        gl.uniform_matrix_4_f32_slice(gl.get_uniform_location(program, "m").as_ref(), false, &flat);

        let positions: Vec<f32> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
        let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
        let vao = gl.create_vertex_array()?;
        gl.bind_vertex_array(Some(vao));
        let vbo = gl.create_buffer()?;
        gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
        gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, bytes(&positions), glow::STATIC_DRAW);
        gl.enable_vertex_attrib_array(0);
        gl.vertex_attrib_pointer_f32(0, 3, glow::FLOAT, false, 12, 0);
        let ibo = gl.create_buffer()?;
        gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, Some(ibo));
        gl.buffer_data_u8_slice(glow::ELEMENT_ARRAY_BUFFER, bytes(&indices), glow::STATIC_DRAW);

        let depth = gl.create_texture()?;
        gl.bind_texture(glow::TEXTURE_2D, Some(depth));
        gl.tex_storage_2d(glow::TEXTURE_2D, 1, glow::DEPTH_COMPONENT24, side, side);
        let fbo = gl.create_framebuffer()?;
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
        gl.framebuffer_texture_2d(glow::FRAMEBUFFER, glow::DEPTH_ATTACHMENT, glow::TEXTURE_2D, Some(depth), 0);
        gl.draw_buffers(&[glow::NONE]);
        gl.read_buffer(glow::NONE);
        if gl.check_framebuffer_status(glow::FRAMEBUFFER) != glow::FRAMEBUFFER_COMPLETE {
            return Err("the depth framebuffer is incomplete".into());
        }
        gl.viewport(0, 0, side, side);
        gl.enable(glow::DEPTH_TEST);
        gl.depth_func(glow::LESS);
        gl.clear_depth_f32(1.0);
        let count = i32::try_from(indices.len()).map_err(|_| "too many indices")?;
        let frame = || {
            gl.clear(glow::DEPTH_BUFFER_BIT);
            gl.draw_elements(glow::TRIANGLES, count, glow::UNSIGNED_INT, 0);
            gl.finish();
        };
        frame();
        let mut ms = Vec::with_capacity(frames);
        for _ in 0..frames {
            let t = Instant::now();
            frame();
            ms.push(t.elapsed().as_secs_f64() * 1e3);
        }
        // Whether any fragment passed (an occlusion query over one more
        // frame): the mesh is in view, not clipped away.
        let query = gl.create_query()?;
        gl.clear(glow::DEPTH_BUFFER_BIT);
        gl.begin_query(glow::ANY_SAMPLES_PASSED, query);
        gl.draw_elements(glow::TRIANGLES, count, glow::UNSIGNED_INT, 0);
        gl.end_query(glow::ANY_SAMPLES_PASSED);
        let passed = gl.get_query_parameter_u32(query, glow::QUERY_RESULT) != 0;
        Ok((ms, passed, renderer))
    }
}

/// The bytes of a slice of plain numbers.
fn bytes<T: Copy>(v: &[T]) -> &[u8] {
    // SAFETY: `T` is f32 or u32 here: plain data without padding, any bit
    // pattern valid as bytes; the slice covers exactly `v`'s memory.
    #[allow(unsafe_code)]
    unsafe {
        std::slice::from_raw_parts(v.as_ptr().cast::<u8>(), std::mem::size_of_val(v))
    }
}
