//! The XDMF sidecar (`snapshots.xdmf`, `snapshots.partial.xdmf`) that lets ParaView (or VTK's
//! `vtkXdmfReader`) open the snapshots.
//!
//! XDMF 3: one Temporal Collection of Uniform grids, one grid per snapshot group, each with its own
//! particle count N: Topology Polyvertex, Geometry XYZ from `/step_XXXXXX/position` (N x 3),
//! Attribute Vector `velocity`, Attribute Tensor `stress` (the Cauchy stress, N x 3 x 3: nine
//! components), one Attribute Scalar per 1-D dataset ([`scalar_datasets`]: `von_mises`, `p`,
//! `eps_p`, ...), and the Time Value of the snapshot. Every attribute carries an
//! `<Information Name="units">` (SI). The Domain starts with `<Information>` elements `status`
//! (`complete` in `snapshots.xdmf`, `partial: ...` with the reason, still running, interrupted or
//! ended without finishing, in `snapshots.partial.xdmf`, which also opens with an XML comment
//! saying so), `gsph_version` and `material_names` (`0: steel, 1: sic`).

use core::fmt::Write as _;

use super::meta::{unit, GSPH_VERSION};
use super::table::FLOAT_COLUMNS;

/// The 1-D datasets of each snapshot group: `id`, `material`, the `final.csv` float columns in
/// their order but the first six (position and velocity, stored as N x 3 datasets `position`
/// and `velocity`), then `von_mises`.
pub fn scalar_datasets() -> impl Iterator<Item = &'static str> + Clone {
    ["id", "material"]
        .into_iter()
        .chain(FLOAT_COLUMNS[6..].iter().copied())
        .chain(["von_mises"])
}

/// The `status` of a complete `snapshots.xdmf`.
pub const STATUS_COMPLETE: &str = "complete";

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

fn attribute(
    out: &mut String,
    h5: &str,
    group: &str,
    name: &str,
    ty: &str,
    dims: &str,
    dim: usize,
) {
    let _ = writeln!(
        out,
        "      <Attribute Name=\"{name}\" AttributeType=\"{ty}\" Center=\"Node\">"
    );
    let u = unit(name, dim);
    if !u.is_empty() {
        let _ = writeln!(out, "        <Information Name=\"units\" Value=\"{u}\"/>");
    }
    data_item(out, h5, group, name, dims);
    out.push_str("      </Attribute>\n");
}

/// What an XDMF document says besides its grids.
#[derive(Debug, Clone, Copy)]
pub struct XdmfHeader<'a> {
    /// The HDF5 file of the heavy data, relative to the XDMF file: `snapshots.h5`, or
    /// `snapshots.partial.h5` while the run goes on.
    pub h5_file: &'a str,
    /// Dimension of the run (the unit of the mass depends on it).
    pub dim: usize,
    /// [`STATUS_COMPLETE`] or a line starting `partial:`.
    pub status: &'a str,
    /// Material names, in the order the `material` attribute indexes.
    pub materials: &'a [String],
}

/// The XDMF document for the snapshots `grids` described by `head`.
pub fn xdmf_document(head: &XdmfHeader, grids: &[XdmfGrid]) -> String {
    let XdmfHeader {
        h5_file,
        dim,
        status,
        materials,
    } = *head;
    let mut out = String::with_capacity(1024 + grids.len() * 5000);
    out.push_str("<?xml version=\"1.0\" ?>\n");
    out.push_str("<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n");
    if status != STATUS_COMPLETE {
        // no `>` or `--` inside a comment
        let text = status.replace("--", "- -").replace('>', " ");
        let _ = writeln!(out, "<!-- PARTIAL OUTPUT, not a finished run: {text} -->");
    }
    out.push_str("<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n");
    out.push_str("  <Domain>\n");
    let _ = writeln!(
        out,
        "    <Information Name=\"status\" Value=\"{}\"/>",
        escape(status)
    );
    let _ = writeln!(
        out,
        "    <Information Name=\"gsph_version\" Value=\"{}\"/>",
        escape(GSPH_VERSION)
    );
    let names: Vec<String> = materials
        .iter()
        .enumerate()
        .map(|(k, m)| format!("{k}: {m}"))
        .collect();
    let _ = writeln!(
        out,
        "    <Information Name=\"material_names\" Value=\"{}\"/>",
        escape(&names.join(", "))
    );
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
        let (vec3, tensor) = (format!("{n} 3"), format!("{n} 3 3"));
        attribute(&mut out, h5_file, &group, "velocity", "Vector", &vec3, dim);
        attribute(&mut out, h5_file, &group, "stress", "Tensor", &tensor, dim);
        for name in scalar_datasets() {
            attribute(
                &mut out,
                h5_file,
                &group,
                name,
                "Scalar",
                &n.to_string(),
                dim,
            );
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
        let materials = ["steel".to_string(), "sic".to_string()];
        let head = XdmfHeader {
            h5_file: "snapshots.h5",
            dim: 2,
            status: STATUS_COMPLETE,
            materials: &materials,
        };
        let x = xdmf_document(&head, &grids);
        assert!(x.contains("<Information Name=\"material_names\" Value=\"0: steel, 1: sic\"/>"));
        check_balanced_tags(&x).unwrap();
        assert!(x.contains("<Information Name=\"status\" Value=\"complete\"/>"));
        assert!(!x.contains("PARTIAL") && !x.contains("partial"));
        assert!(x.contains(&format!("Name=\"gsph_version\" Value=\"{GSPH_VERSION}\"")));
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
            2 * scalar_datasets().count()
        );
        assert_eq!(x.matches("AttributeType=\"Vector\"").count(), 2);
        assert_eq!(x.matches("AttributeType=\"Tensor\"").count(), 2);
        assert!(x.contains("<Attribute Name=\"stress\" AttributeType=\"Tensor\" Center=\"Node\">\n        <Information Name=\"units\" Value=\"Pa\"/>\n        <DataItem Dimensions=\"3 3 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">snapshots.h5:/step_001234/stress<"));
        assert!(x.contains("<Attribute Name=\"von_mises\" AttributeType=\"Scalar\" Center=\"Node\">\n        <Information Name=\"units\" Value=\"Pa\"/>"));
        assert!(x.contains("<Attribute Name=\"m\" AttributeType=\"Scalar\" Center=\"Node\">\n        <Information Name=\"units\" Value=\"kg/m\"/>"));
        // labels carry no units
        assert!(x.contains(
            "<Attribute Name=\"id\" AttributeType=\"Scalar\" Center=\"Node\">\n        <DataItem"
        ));
    }

    #[test]
    fn partial_documents_say_so_twice() {
        let grids = [XdmfGrid {
            step: 7,
            time: 1e-6,
            n: 2,
        }];
        let status = "partial: interrupted at step 7, t = 1e-6 s <SIGTERM> -- \"now\"";
        let head = XdmfHeader {
            h5_file: "snapshots.partial.h5",
            dim: 3,
            status,
            materials: &[],
        };
        let x = xdmf_document(&head, &grids);
        assert!(x.contains("<Information Name=\"material_names\" Value=\"\"/>"));
        check_balanced_tags(&x).unwrap();
        assert!(
            x.contains("<!-- PARTIAL OUTPUT, not a finished run: partial: interrupted at step 7")
        );
        assert!(x.contains(
            "<Information Name=\"status\" Value=\"partial: interrupted at step 7, t = 1e-6 s \
             &lt;SIGTERM&gt; -- &quot;now&quot;\"/>"
        ));
        assert!(x.contains(">snapshots.partial.h5:/step_000007/stress<"));
        assert!(x.contains("<Information Name=\"units\" Value=\"kg\"/>"));
        let comment = x.lines().find(|l| l.starts_with("<!--")).unwrap();
        assert!(!comment[4..comment.len() - 3].contains("--"), "{comment}");
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
