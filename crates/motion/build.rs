//! Declares every file in `src/plugins/` as a module (see `plugin_dir`): a motion model is one
//! file dropped there, with no `mod` line to edit anywhere else.

fn main() -> std::io::Result<()> {
    plugin_dir::declare_plugins()
}
