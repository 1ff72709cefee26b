import { ActionIcon, Badge, Button, NativeSelect, NumberInput, SegmentedControl, Table, createTheme } from "@mantine/core";

/** Light, dense engineering-tool look: small controls, tabular numbers. */
export const theme = createTheme({
  primaryColor: "blue",
  defaultRadius: "sm",
  fontFamily:
    "Inter, system-ui, -apple-system, 'Segoe UI', Roboto, 'Helvetica Neue', Arial, 'Noto Sans', 'Liberation Sans', sans-serif",
  fontFamilyMonospace: "'JetBrains Mono', 'DejaVu Sans Mono', 'Liberation Mono', Menlo, Consolas, monospace",
  headings: { sizes: { h5: { fontSize: "0.875rem" } } },
  components: {
    Button: Button.extend({ defaultProps: { size: "xs" } }),
    ActionIcon: ActionIcon.extend({ defaultProps: { size: "md", variant: "subtle" } }),
    NumberInput: NumberInput.extend({ defaultProps: { size: "xs", hideControls: true } }),
    NativeSelect: NativeSelect.extend({ defaultProps: { size: "xs" } }),
    SegmentedControl: SegmentedControl.extend({ defaultProps: { size: "xs" } }),
    Badge: Badge.extend({ defaultProps: { radius: "sm" } }),
    Table: Table.extend({ defaultProps: { fz: "xs", verticalSpacing: 4, horizontalSpacing: 8 } }),
  },
});
