//! The gearing an experiment runs on: the embedded Freeth 2006 data, or a user's RON file given
//! with `--set gearing=FILE`.

use registry::{Context, Param, RunError};
use train::Gearing;

/// The `gearing` parameter every train experiment declares.
pub const PARAM: Param = Param {
    name: "gearing",
    default: "freeth2006",
    unit: "",
    help: "gearing RON file (default: the embedded Freeth 2006 data, crates/train/data/freeth2006.ron)",
};

/// Clearance G of every mesh of the gearing (the paper's working value, Appendix II).
pub const CLEARANCE: Param = Param {
    name: "clearance",
    default: "40",
    unit: "% of h",
    help: "clearance G of every mesh",
};

/// Tooth height h of every gear.
pub const TOOTH_HEIGHT: Param = Param {
    name: "tooth_height",
    default: "1.1",
    unit: "mm",
    help: "h = R - r of every gear (Efstathiou et al. 2012)",
};

/// Loads the gearing named by the `gearing` parameter.
pub fn load(ctx: &Context) -> Result<Gearing, RunError> {
    let name = ctx.param("gearing")?;
    if name == PARAM.default {
        return Ok(Gearing::freeth2006());
    }
    Gearing::load(std::path::Path::new(name)).map_err(|e| RunError::bad(e.file, e.location, e.rule))
}
