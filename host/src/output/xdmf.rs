//! The XDMF sidecar (`snapshots.xdmf`) that lets ParaView open `snapshots.h5`.
//!
//! XDMF 3: one Temporal Collection of Uniform grids, one grid per snapshot group, each with its own
//! particle count N: Topology Polyvertex, Geometry XYZ from `/step_XXXXXX/position` (N x 3),
//! Attribute Vector `velocity`, one Attribute Scalar per 1-D dataset, and the Time Value of the
//! snapshot.

use core::fmt::Write as _;

/// The 1-D datasets of each snapshot group, in `final.csv` column order (position and velocity are
/// stored as N x 3 datasets `position` and `velocity`).
pub const SCALAR_DATASETS: [&str; 16] = [
    "id",
    "material",
    "m",
    "rho",
    "p",
    "e",
    "sxx",
    "syy",
    "szz",
    "sxy",
    "sxz",
    "syz",
    "eps_p",
    "damage",
    "temperature",
    "h",
];

/// The HDF5 group name of a snapshot: `step_000123` (at least six digits).
pub fn group_name(step: u64) -> String {
    format!("step_{step:06}")
}

/// One snapshot as the XDMF sidecar sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct XdmfGrid {
    /// Step number (names the group).
    pub step: u64,
    /// Simulation time (s).
    pub time: f64,
    /// Number of particles in this snapshot.
    pub n: usize,
}

/// XDMF number type and precision of a dataset.
fn number_type(name: &str) -> (&'static str, u32) {
    match name {
        "id" | "material" => ("UInt", 4),
        _ => ("Float", 8),
    }
}

/// Escapes the characters XML reserves in attribute values and text.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            _ => out.push(c),
        }
    }
    out
}

fn data_item(out: &mut String, h5_file: &str, group: &str, dataset: &str, dims: &str) {
    let (ty, prec) = number_type(dataset);
    let _ = writeln!(
        out,
        "        <DataItem Dimensions=\"{dims}\" NumberType=\"{ty}\" Precision=\"{prec}\" \
         Format=\"HDF\">{}:/{group}/{dataset}</DataItem>",
        escape(h5_file)
    );
}

/// The XDMF document for `grids`, whose heavy data live in `h5_file` (a path relative to the XDMF
/// file, normally `snapshots.h5`).
pub fn xdmf_document(h5_file: &str, grids: &[XdmfGrid]) -> String {
    let mut out = String::with_capacity(1024 + grids.len() * 3000);
    out.push_str("<?xml version=\"1.0\" ?>\n");
    out.push_str("<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n");
    out.push_str("<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n");
    out.push_str("  <Domain>\n");
    out.push_str(
        "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
    );
    for g in grids {
        let group = group_name(g.step);
        let n = g.n;
        let _ = writeln!(out, "    <Grid Name=\"{group}\" GridType=\"Uniform\">");
        let _ = writeln!(out, "      <Time Value=\"{:e}\"/>", g.time);
        let _ = writeln!(
            out,
            "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{n}\" \
             NodesPerElement=\"1\"/>"
        );
        out.push_str("      <Geometry GeometryType=\"XYZ\">\n");
        data_item(&mut out, h5_file, &group, "position", &format!("{n} 3"));
        out.push_str("      </Geometry>\n");
        out.push_str(
            "      <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n",
        );
        data_item(&mut out, h5_file, &group, "velocity", &format!("{n} 3"));
        out.push_str("      </Attribute>\n");
        for name in SCALAR_DATASETS {
            let _ = writeln!(
                out,
                "      <Attribute Name=\"{name}\" AttributeType=\"Scalar\" Center=\"Node\">"
            );
            data_item(&mut out, h5_file, &group, name, &n.to_string());
            out.push_str("      </Attribute>\n");
        }
        out.push_str("    </Grid>\n");
    }
    out.push_str("    </Grid>\n");
    out.push_str("  </Domain>\n");
    out.push_str("</Xdmf>\n");
    out
}

/// Checks that the element tags of an XML document are balanced and properly nested (a minimal
/// well-formedness check: comments, CDATA and quoted `>` inside attributes are not handled).
pub fn check_balanced_tags(xml: &str) -> Result<(), String> {
    let mut stack: Vec<&str> = Vec::new();
    let mut rest = xml;
    while let Some(start) = rest.find('<') {
        let after = &rest[start + 1..];
        let end = after.find('>').ok_or("unterminated tag")?;
        let tag = &after[..end];
        rest = &after[end + 1..];
        if tag.starts_with('?') || tag.starts_with('!') {
            continue;
        }
        if let Some(closing) = tag.strip_prefix('/') {
            let open = stack
                .pop()
                .ok_or_else(|| format!("unexpected </{closing}>"))?;
            if open != closing.trim() {
                return Err(format!("<{open}> closed by </{closing}>"));
            }
        } else if !tag.ends_with('/') {
            let name = tag.split(|c: char| c.is_whitespace() || c == '/').next();
            stack.push(name.unwrap_or(""));
        }
    }
    match stack.last() {
        Some(open) => Err(format!("<{open}> not closed")),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn document_is_balanced_and_complete() {
        let grids = [
            XdmfGrid {
                step: 0,
                time: 0.0,
                n: 5,
            },
            XdmfGrid {
                step: 1234,
                time: 2.5e-6,
                n: 3,
            },
        ];
        let x = xdmf_document("snapshots.h5", &grids);
        check_balanced_tags(&x).unwrap();
        assert!(x.contains("CollectionType=\"Temporal\""));
        assert_eq!(x.matches("GridType=\"Uniform\"").count(), 2);
        assert!(x.contains("<Time Value=\"0e0\"/>"));
        assert!(x.contains("<Time Value=\"2.5e-6\"/>"));
        assert!(x.contains("NumberOfElements=\"5\""));
        assert!(x.contains("NumberOfElements=\"3\""));
        assert!(x.contains("Dimensions=\"5 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">snapshots.h5:/step_000000/position<"));
        assert!(x.contains(">snapshots.h5:/step_001234/velocity<"));
        assert!(x.contains("Dimensions=\"3\" NumberType=\"UInt\" Precision=\"4\" Format=\"HDF\">snapshots.h5:/step_001234/id<"));
        assert_eq!(
            x.matches("AttributeType=\"Scalar\"").count(),
            2 * SCALAR_DATASETS.len()
        );
    }

    #[test]
    fn balance_checker_rejects_broken_xml() {
        assert!(check_balanced_tags("<a><b></a></b>").is_err());
        assert!(check_balanced_tags("<a><b/>").is_err());
        assert!(check_balanced_tags("</a>").is_err());
        assert!(check_balanced_tags("<?xml ?><a x=\"1\"><b/></a>").is_ok());
    }

    #[test]
    fn group_names() {
        assert_eq!(group_name(123), "step_000123");
        assert_eq!(group_name(12_345_678), "step_12345678");
    }
}
