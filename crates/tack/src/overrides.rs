//! `--set key.path=value` overrides, applied to the TOML document before it is deserialised.
//!
//! The key is a dotted path (`roughness.h`, `grid.n`); missing intermediate tables are created.
//! The value is parsed as a TOML value (number, boolean, string, array, inline table, `nan`,
//! `inf`) and falls back to a plain string, so `geometry.shape=sphere` works without quotes.
//! Keys the schema does not know are then rejected by the schema (unknown field).

use tack_fields as fields;

use crate::error::SceneError;

/// Applies every override in order to `table`.
pub fn apply_overrides(table: &mut toml::Table, overrides: &[String]) -> Result<(), SceneError> {
    for assignment in overrides {
        apply_one(table, assignment)?;
    }
    Ok(())
}

/// Parses `value` as a TOML value, falling back to a string.
pub fn parse_value(value: &str) -> toml::Value {
    let value = value.trim();
    toml::from_str::<toml::Table>(&format!("v = {value}"))
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(value.to_owned()))
}

fn apply_one(table: &mut toml::Table, assignment: &str) -> Result<(), SceneError> {
    let (key, value) = assignment
        .split_once('=')
        .ok_or_else(|| SceneError::Override {
            assignment: assignment.to_owned(),
            reason: format!("expected key=value, e.g. {}=0.002", fields::ROUGHNESS_H),
        })?;
    set_path(table, key, parse_value(value), assignment)
}

/// Sets the dotted `key` (`roughness.h`) of `table` to an already typed `value`, exactly as
/// `--set key=value` would (missing tables are created); parameter sweeps use it so that values
/// need no round trip through text. Errors are [`SceneError::Override`] naming `key=value`.
pub fn set_value(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<(), SceneError> {
    let assignment = format!("{key}={value}");
    set_path(table, key, value, &assignment)
}

fn set_path(
    table: &mut toml::Table,
    key: &str,
    value: toml::Value,
    assignment: &str,
) -> Result<(), SceneError> {
    let fail = |reason: String| SceneError::Override {
        assignment: assignment.to_owned(),
        reason,
    };
    let parts: Vec<&str> = key.trim().split('.').map(str::trim).collect();
    if parts.iter().any(|p| p.is_empty()) {
        return Err(fail(format!(
            "`{}` is not a dotted key like `{gamma}`",
            key.trim(),
            gamma = fields::MATERIAL_GAMMA
        )));
    }
    let (last, parents) = parts.split_last().ok_or_else(|| fail("empty key".into()))?;
    let mut current = table;
    for (depth, part) in parents.iter().enumerate() {
        let entry = current
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        current = entry.as_table_mut().ok_or_else(|| {
            fail(format!(
                "`{}` is a value, not a table",
                parts[..=depth].join(".")
            ))
        })?;
    }
    current.insert(last.to_string(), value);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> toml::Table {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn values_parse_as_toml_then_string() {
        assert_eq!(parse_value("0.002"), toml::Value::Float(0.002));
        assert_eq!(parse_value("3"), toml::Value::Integer(3));
        assert_eq!(parse_value("true"), toml::Value::Boolean(true));
        assert_eq!(parse_value("sphere"), toml::Value::String("sphere".into()));
        assert_eq!(parse_value("\"a b\""), toml::Value::String("a b".into()));
        assert!(parse_value("nan").as_float().unwrap().is_nan());
        assert_eq!(
            parse_value("[1, 2]"),
            toml::Value::Array(vec![1.into(), 2.into()])
        );
    }

    #[test]
    fn dotted_keys_set_and_create_tables() {
        let mut t = table("[material]\ngamma = 1.0\n");
        apply_overrides(
            &mut t,
            &["material.gamma=0.5".into(), "roughness.h = 2e-3".into()],
        )
        .unwrap();
        assert_eq!(t["material"]["gamma"].as_float(), Some(0.5));
        assert_eq!(t["roughness"]["h"].as_float(), Some(2e-3));
    }

    #[test]
    fn typed_values_set_like_overrides() {
        let mut t = table("[material]\ngamma = 1.0\n");
        set_value(&mut t, "material.gamma", toml::Value::Float(0.1 + 0.2)).unwrap();
        set_value(&mut t, "roughness.seed", toml::Value::Integer(7)).unwrap();
        assert_eq!(t["material"]["gamma"].as_float(), Some(0.1 + 0.2));
        assert_eq!(t["roughness"]["seed"].as_integer(), Some(7));
        let e = set_value(&mut t, "material.gamma.x", 1.into()).unwrap_err();
        assert!(e.to_string().starts_with("--set material.gamma.x=1"), "{e}");
    }

    #[test]
    fn bad_overrides_name_themselves() {
        let mut t = table("version = 1\n");
        for bad in ["novalue", "version.x=1", ".a=1", "a..b=2"] {
            let e = apply_overrides(&mut t, &[bad.into()])
                .unwrap_err()
                .to_string();
            assert!(e.starts_with(&format!("--set {bad}")), "{e}");
        }
    }
}
