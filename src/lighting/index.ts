export { buildAliasTable, aliasTableDistribution, type AliasTable } from './alias-table.ts';
export { buildEmissiveLightTable, type EmissiveLightTable, type EmissiveTriangleInput } from './emissive-lights.ts';
